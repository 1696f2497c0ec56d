#pragma once
// UDP datagrams over POSIX sockets, IPv4 only: the transport of the live packet format.

#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace tactile {

struct UdpEndpoint {
  std::string host;  // dotted IPv4 address ("localhost" is read as 127.0.0.1)
  uint16_t port = 0;
  std::string url() const { return "udp://" + host + ":" + std::to_string(port); }
};

// Where a URL is used: sent to (a port must be named), or listened on (port 0: any free port,
// which the socket then reports: UdpSocket::local_port()).
enum class UdpUse { kSend, kListen };

// Parses "udp://HOST:PORT" (HOST a dotted IPv4 address or "localhost", PORT 1-65535, or 0 to
// listen on any free port). Throws tactile::Error at `option` (e.g. "--to") saying what is
// wrong with the URL.
UdpEndpoint parse_udp_url(const std::string& url, const std::string& option, UdpUse use);

// One UDP socket, closed on destruction. Errors throw tactile::Error naming the endpoint.
class UdpSocket {
 public:
  // A socket whose datagrams go to `destination`.
  static UdpSocket connect_to(const UdpEndpoint& destination);
  // A socket bound to `local` (port 0: any free port, see local_port()).
  static UdpSocket bind_to(const UdpEndpoint& local);

  UdpSocket(UdpSocket&& other) noexcept;
  UdpSocket& operator=(UdpSocket&& other) noexcept;
  UdpSocket(const UdpSocket&) = delete;
  UdpSocket& operator=(const UdpSocket&) = delete;
  ~UdpSocket();

  // Sends one datagram. A refused destination (nobody listening on loopback) is not an
  // error for a sender of live data: the datagram is gone, as on a real network; it returns
  // false then.
  bool send(std::span<const uint8_t> datagram);
  // Waits up to `timeout_seconds` for one datagram; its size, or nullopt on timeout. A
  // datagram longer than `buffer` is reported with its full length (> buffer.size()).
  std::optional<size_t> receive(std::span<uint8_t> buffer, double timeout_seconds);
  uint16_t local_port() const;

 private:
  UdpSocket(int descriptor, std::string where)
      : descriptor_(descriptor), where_(std::move(where)) {}
  int descriptor_ = -1;
  std::string where_;
};

}  // namespace tactile
