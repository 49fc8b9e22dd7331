#include "pbrt_ext/images/imagecodec.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace pbrt {

namespace {

constexpr const char *kModuleName = "libpbrt_ext_imagecodec.so";

std::vector<std::string> ModuleCandidates() {
    std::vector<std::string> candidates;
    if (const char *env = std::getenv("PBRT_EXT_IMAGE_CODEC"); env && *env) candidates.push_back(env);
    std::error_code ec;
    std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) candidates.push_back((exe.parent_path() / ".." / PBRT_EXT_IMAGE_CODEC_INSTALL_DIR / kModuleName).lexically_normal());
    candidates.push_back(PBRT_EXT_IMAGE_CODEC_BUILD_PATH);
    return candidates;
}

const ImageCodec *LoadImageCodec() {
    std::string tried;
    for (const std::string &path : ModuleCandidates()) {
        void *module = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!module) {
            tried += "\n  " + path + ": " + dlerror();
            continue;
        }
        using Entry = const ImageCodec *(*)();
        if (auto entry = reinterpret_cast<Entry>(dlsym(module, "pbrt_ext_image_codec"))) return entry();
        tried += "\n  " + path + ": no pbrt_ext_image_codec in it";
    }
    throw std::runtime_error("cannot load the OpenImageIO module for images other than EXR "
                             "output; tried (set PBRT_EXT_IMAGE_CODEC to its path):" + tried);
}

}  // namespace

const ImageCodec &GetImageCodec() {
    static const ImageCodec *codec = LoadImageCodec();
    return *codec;
}

}  // namespace pbrt
