// Scene files written by a test into its own temporary folder, and the error loading one gives.
#pragma once

#include "pbrt_ext/scene/sceneloader.h"
#include "pbrt_ext/util/error.h"

#include <filesystem>
#include <string>

namespace pbrt {

// A fresh folder of the system's temporary directory for the test's files.
inline std::filesystem::path TestFolder(const std::string &name) {
    std::filesystem::path dir = std::filesystem::temp_directory_path() / name;
    std::filesystem::create_directories(dir);
    return dir;
}

// What LoadScene reports for the scene file after its path (":line:col: error: ..."), or
// "no error".
inline std::string LoadErrorAfterPath(const std::string &scene,
                                      const RenderOverrides &overrides = {}) {
    try {
        LoadScene(scene, overrides);
    } catch (const ParseError &e) {
        return std::string(e.what()).substr(scene.size());
    }
    return "no error";
}

}  // namespace pbrt
