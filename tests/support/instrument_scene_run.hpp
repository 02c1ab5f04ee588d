// A shipped scene with instruments, played as `filum run` plays it: the scene, its instruments
// (InstrumentSet: their drivers before each step, their jaws and metrics after it) and lookups of
// its components by type (obstacles, force fields).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "filum/all_components.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/core/scene_loader.hpp"
#include "filum/haptics/instrument_set.hpp"

namespace filum::test {

struct InstrumentSceneRun {
  std::unique_ptr<Scene> scene;
  std::unique_ptr<haptics::InstrumentSet> instruments;

  /// apps/scenes/<file> of the source tree.
  explicit InstrumentSceneRun(const std::string& file) {
    const std::string path = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/" + file;
    const nlohmann::json document = readJsonFile(path);
    scene = loadScene(document, path, app::makeFactory());
    instruments = haptics::InstrumentSet::fromScene(document, path, *scene);
    scene->init();
  }
  /// One step with the instruments' work around it; false when the step failed.
  bool step() {
    instruments->beforeStep(*scene);
    if (!scene->step().ok) return false;
    instruments->afterStep(*scene);
    return true;
  }
  long steps() const { return std::lround(scene->settings().duration / scene->settings().dt); }
  const CurveBody& body(int k = 0) const { return *scene->bodies()[k]->curve(); }
  int instrumentIndex(const std::string& name) const {
    for (int i = 0; i < instruments->size(); ++i)
      if (instruments->instrument(i).name() == name) return i;
    return -1;
  }
  /// Every component of type T in the scene's nodes.
  template <class T>
  std::vector<const T*> components() const {
    std::vector<const T*> out;
    collect(scene->root(), out);
    return out;
  }
  /// The first force field of type T (nullptr: none).
  template <class T>
  const T* forceField() const {
    for (const ForceField* field : scene->forceFields())
      if (const auto* f = dynamic_cast<const T*>(field)) return f;
    return nullptr;
  }

 private:
  template <class T>
  static void collect(const Node& node, std::vector<const T*>& out) {
    for (const auto& component : node.components())
      if (const auto* c = dynamic_cast<const T*>(component.get())) out.push_back(c);
    for (const auto& child : node.children()) collect(*child, out);
  }
};

}  // namespace filum::test
