// pbrt-v4's --display-server: the image being rendered, streamed to tev (github.com/Tom94/tev)
// with tev's published IPC protocol, as pbrt-v4 streams it.
//
// Over TCP, a packet is its length (uint32, the whole packet's bytes), its type (uint8) and its
// payload; integers are little-endian int32, strings NUL-terminated, pixels float32.
//  - CreateImage (4): grab focus (uint8), image name, width, height, channel count, channel names.
//  - UpdateImage (3): grab focus (uint8), image name, channel name, x, y, width, height, then
//    width x height values of the channel, row by row.
#pragma once

#include "pbrt_ext/images/image.h"

#include <cstdint>
#include <string>
#include <vector>

namespace pbrt {

enum class TevPacket : uint8_t { UpdateImage = 3, CreateImage = 4 };

class TevClient {
  public:
    // "host:port"; throws std::runtime_error naming it and the reason when it can't connect.
    explicit TevClient(const std::string &address);
    ~TevClient();
    TevClient(const TevClient &) = delete;
    TevClient &operator=(const TevClient &) = delete;

    // The image under this name: created in tev on the first call, then sent as R, G and B
    // tiles of at most kTileSize^2 pixels. Throws std::runtime_error when the viewer has gone.
    void Show(const std::string &name, const Image &image);

    static constexpr int kTileSize = 128;

  private:
    void Send(const std::vector<uint8_t> &packet);
    int socket = -1;
    Point2i created{-1, -1};  // the resolution tev holds the image at
};

}  // namespace pbrt
