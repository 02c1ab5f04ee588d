// `filum check`: loads a scene and checks everything `filum run` (with --meshes or --render) and
// `filum view` would read — the scene, its "output" block, its "camera" and the visual models
// bound to the bodies and constraints they follow — without simulating it.
#pragma once

#include <iosfwd>
#include <string>

namespace filum::app {

/// 0 and a one-line summary when the scene is good; 2 and "error: <place>: ..." otherwise.
int checkScene(const std::string& path, std::ostream& out);

}  // namespace filum::app
