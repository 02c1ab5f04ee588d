#include "filum/check_command.hpp"

#include <iostream>

#include "filum/all_components.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/core/scene_loader.hpp"
#include "filum/haptics/fluoroscopy_pedal.hpp"
#include "filum/haptics/haptic_session.hpp"
#include "filum/haptics/hub_device.hpp"
#include "filum/haptics/instrument_set.hpp"
#include "filum/output_settings.hpp"
#include "filum/physics_check.hpp"
#include "filum/run_command.hpp"
#include "filum/visual/camera.hpp"
#include "filum/visual/fluoroscopy_view.hpp"
#include "filum/visual/visual_scene.hpp"

namespace filum::app {

int checkScene(const std::string& path, std::ostream& out) {
  try {
    const nlohmann::json document = readJsonFile(path);
    auto scene = loadScene(document, path, makeFactory());
    readOutputSettings(document, path);  // read by `filum run`
    visual::readCamera(document, path);  // read by --render and `filum view`
    visual::FluoroscopyView::fromScene(document, path);    // the C-arm's view, read by --render
    haptics::FluoroscopyPedal::fromScene(document, path);  // and its pedal (also the metrics')
    haptics::HubDevice::fromScene(document, path, *scene, 0.0);  // a device at a catheter's hub ("navigation")
    // The "haptics" block, read by `filum run` (a Phantom is opened, then closed, to check it).
    haptics::HapticSession::fromScene(document, path, *scene, 0.0);  // (no run: the shortest servo log)
    haptics::InstrumentSet::fromScene(document, path, *scene);  // the "instruments", read by `filum run`
    visual::VisualScene visuals(*scene);  // binds what the visual models follow (--meshes, --render, view)
    visuals.update(scene->state());
    // Physics mistakes: what is well-formed but cannot run as written (physics_check.hpp).
    const std::vector<std::string> problems = physicsProblems(*scene, document);
    if (!problems.empty()) {
      for (const std::string& p : problems) out << "error: " << p << '\n';
      return kRunSceneError;
    }
    out << path << ": ok (" << scene->bodies().size() << " bodies, " << scene->dofPointCount() << " control points, "
        << scene->constraints().size() << " constraints)\n";
    for (const std::string& line : scaleSummary(*scene)) out << "  " << line << '\n';
    return 0;
  } catch (const SceneError& e) {
    out << "error: " << e.what() << '\n';
    return kRunSceneError;
  } catch (const std::exception& e) {  // a check missing in the loader: still the file, never an abort
    out << "error: " << path << ": cannot load the scene: " << e.what() << '\n';
    return kRunSceneError;
  }
}

}  // namespace filum::app
