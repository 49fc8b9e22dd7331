#include "pbrt_ext/cmd/tevclient.h"

#include <netdb.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace pbrt {

namespace {

static_assert(std::endian::native == std::endian::little, "tev's integers are little-endian");

// A packet under construction: its length (the first 4 bytes) is filled in by Finish.
class PacketWriter {
  public:
    explicit PacketWriter(TevPacket type) : bytes(5) { bytes[4] = uint8_t(type); }
    template <typename T>
    void Put(T value) {
        Append(&value, sizeof(T));
    }
    void Put(const std::string &s) { Append(s.c_str(), s.size() + 1); }  // with its NUL
    std::vector<uint8_t> Finish() {
        uint32_t length = uint32_t(bytes.size());
        std::memcpy(bytes.data(), &length, sizeof(length));
        return std::move(bytes);
    }

  private:
    // resize and memcpy: GCC 12 misreads vector<uint8_t>::insert from a pointer as an overflow.
    void Append(const void *data, size_t size) {
        const size_t at = bytes.size();
        bytes.resize(at + size);
        std::memcpy(bytes.data() + at, data, size);
    }
    std::vector<uint8_t> bytes;
};

int Connect(const std::string &address) {
    size_t colon = address.rfind(':');
    if (colon == std::string::npos || colon == 0 || colon + 1 == address.size())
        throw std::runtime_error("--display-server: \"" + address + "\": expected host:port");
    std::string host = address.substr(0, colon), port = address.substr(colon + 1);
    addrinfo hints{};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    addrinfo *found = nullptr;
    if (int e = ::getaddrinfo(host.c_str(), port.c_str(), &hints, &found); e != 0)
        throw std::runtime_error("--display-server: " + address + ": " + ::gai_strerror(e));
    std::string why = "no address";
    int fd = -1;
    for (addrinfo *a = found; a && fd < 0; a = a->ai_next) {
        fd = ::socket(a->ai_family, a->ai_socktype | SOCK_CLOEXEC, a->ai_protocol);
        if (fd >= 0 && ::connect(fd, a->ai_addr, a->ai_addrlen) != 0) {
            why = std::strerror(errno);
            ::close(fd);
            fd = -1;
        }
    }
    ::freeaddrinfo(found);
    if (fd < 0)
        throw std::runtime_error("--display-server: cannot connect to " + address + ": " + why);
    return fd;
}

}  // namespace

TevClient::TevClient(const std::string &address) : socket(Connect(address)) {}

TevClient::~TevClient() {
    if (socket >= 0) ::close(socket);
}

void TevClient::Send(const std::vector<uint8_t> &packet) {
    for (size_t sent = 0; sent < packet.size();) {
        // MSG_NOSIGNAL: a viewer that has gone is an error here, not a SIGPIPE.
        ssize_t n = ::send(socket, packet.data() + sent, packet.size() - sent, MSG_NOSIGNAL);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) throw std::runtime_error(std::string("display server: ") + std::strerror(errno));
        sent += size_t(n);
    }
}

void TevClient::Show(const std::string &name, const Image &image) {
    const Point2i res = image.Resolution();
    const char *channels[] = {"R", "G", "B"};
    if (created != res) {
        PacketWriter create(TevPacket::CreateImage);
        create.Put(uint8_t(1));  // grab focus
        create.Put(name);
        create.Put(int32_t(res.x));
        create.Put(int32_t(res.y));
        create.Put(int32_t(3));
        for (const char *channel : channels) create.Put(std::string(channel));
        Send(create.Finish());
        created = res;
    }
    for (int y0 = 0; y0 < res.y; y0 += kTileSize)
        for (int x0 = 0; x0 < res.x; x0 += kTileSize) {
            const int w = std::min(kTileSize, res.x - x0), h = std::min(kTileSize, res.y - y0);
            for (int c = 0; c < 3; ++c) {
                PacketWriter update(TevPacket::UpdateImage);
                update.Put(uint8_t(0));
                update.Put(name);
                update.Put(std::string(channels[c]));
                for (int32_t v : {x0, y0, w, h}) update.Put(v);
                for (int y = y0; y < y0 + h; ++y)
                    for (int x = x0; x < x0 + w; ++x) update.Put(float(image.GetChannel(Point2i(x, y), c)));
                Send(update.Finish());
            }
        }
}

}  // namespace pbrt
