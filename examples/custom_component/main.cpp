// custom_component: a filum application with a force field of its own (anchor_spring.hpp):
//   custom_component <scene.json>
// registers AnchorSpring beside every component of the installed filum, loads the scene file,
// runs it for its "duration" and reports each AnchorSpring's tension against the weight of its
// body: a body hanging from one spring alone (thread_on_a_spring.json) settles with the two equal,
// its elastic forces summing to zero.
// Exit status: 0 when they balance (to 0.1 %), 1 when a step fails or they do not, 2 when the
// scene does not load (filum::SceneError: the message names the file, the JSON path, what was
// expected and what was found).
#include <cmath>
#include <cstdio>
#include <vector>

#include "anchor_spring.hpp"
#include "filum/all_components.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/core/mechanical_state.hpp"
#include "filum/core/node.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/core/scene_loader.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s <scene.json>\n", argv[0]);
    return 2;
  }
  try {
    filum::Factory factory = filum::app::makeFactory();  // every component of the installed filum
    factory.add("AnchorSpring", "a zero-length spring from a point of a curve to a fixed anchor",
                [](const filum::Params& p) { return custom_component::AnchorSpring::fromParams(p); });
    std::unique_ptr<filum::Scene> scene = filum::loadScene(argv[1], factory);

    const long steps = std::lround(scene->settings().duration / scene->settings().dt);
    for (long i = 0; i < steps; ++i) {
      const filum::StepReport report = scene->step();
      if (!report.ok) {  // the scene was rolled back to the state before that step
        std::fprintf(stderr, "step %ld at t = %g s failed (%s): %s\n", report.step, report.time,
                     report.culprit.c_str(), report.message.c_str());
        return 1;
      }
    }

    std::vector<custom_component::AnchorSpring*> springs;
    scene->root().collect(springs);
    bool balanced = !springs.empty();
    for (const custom_component::AnchorSpring* spring : springs) {
      const double tension = spring->tension(scene->state());
      const double weight = spring->body().curve()->mass() * scene->settings().gravity.norm();
      balanced = balanced && std::abs(tension - weight) <= 1e-3 * weight;
      std::printf("%s on %s: tension %.6g N, weight %.6g N\n", spring->name().c_str(),
                  spring->body().node()->path().c_str(), tension, weight);
    }
    std::printf("t = %.3g s, %ld steps: %s\n", scene->state().time, steps,
                balanced ? "the springs carry the weight" : "FAILED: the springs do not carry the weight");
    return balanced ? 0 : 1;
  } catch (const filum::SceneError& e) {
    std::fprintf(stderr, "scene error: %s\n", e.what());
    return 2;
  }
}
