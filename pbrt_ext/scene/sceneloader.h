// From a pbrt-v4 scene file to a render-ready Scene: parse it into a SceneDescription, then create
// through SceneBuilder only what the scene references (pbrt-v4's BasicScene::Create*). Every
// parameter of every entity is read with pbrt-v4's name and default; one that nothing reads is an
// error at its location, and a feature this renderer lacks is a warning with its location.
#pragma once

#include "pbrt_ext/options.h"
#include "pbrt_ext/scene.h"
#include "pbrt_ext/scene/parser.h"

#include <memory>
#include <string>
#include <vector>

namespace pbrt {

// Throws ParseError ("file:line:col: error: ...") for bad input, std::runtime_error for I/O.
std::unique_ptr<Scene> LoadScene(const std::string &filename, const RenderOverrides &overrides);
// Several files in order, as one scene (pbrt-v4's `pbrt a.pbrt b.pbrt`); relative paths resolve
// against the first one's folder, or the current one for text from standard input. The scene's
// Option directives win over the overrides, as in pbrt-v4.
std::unique_ptr<Scene> LoadScene(const std::vector<SceneFile> &files, const RenderOverrides &overrides);

}  // namespace pbrt
