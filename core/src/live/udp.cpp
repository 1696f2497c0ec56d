#include "tactile/live/udp.h"

#include <arpa/inet.h>
#include <errno.h>
#include <netinet/in.h>
#include <poll.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include <charconv>
#include <cmath>
#include <utility>

#include "tactile/error.h"

namespace tactile {

UdpEndpoint parse_udp_url(const std::string& url, const std::string& option, UdpUse use) {
  const std::string scheme = "udp://";
  if (url.rfind(scheme, 0) != 0)
    throw Error(option, "\"" + url + "\" is not a udp://HOST:PORT URL");
  const std::string rest = url.substr(scheme.size());
  const size_t colon = rest.rfind(':');
  if (colon == std::string::npos || colon == 0)
    throw Error(option, "\"" + url + "\" lacks HOST:PORT (e.g. udp://127.0.0.1:9000)");
  UdpEndpoint endpoint;
  endpoint.host = rest.substr(0, colon);
  if (endpoint.host == "localhost") endpoint.host = "127.0.0.1";
  in_addr address{};
  if (inet_pton(AF_INET, endpoint.host.c_str(), &address) != 1)
    throw Error(option,
                "host \"" + endpoint.host + "\" in \"" + url + "\" is not a dotted IPv4 address");
  const std::string port_text = rest.substr(colon + 1);
  long port = 0;
  const auto [end, failure] =
      std::from_chars(port_text.data(), port_text.data() + port_text.size(), port);
  if (port_text.empty() || failure != std::errc() || end != port_text.data() + port_text.size())
    throw Error(option, "port \"" + port_text + "\" in \"" + url + "\" is not a whole number");
  if (port == 0 && use == UdpUse::kSend)
    throw Error(option, "port 0 in \"" + url + "\" names no port to send to (1-65535)");
  if (port < 0 || port > 65535)
    throw Error(option, "port " + port_text + " in \"" + url + "\" is not in " +
                            (use == UdpUse::kListen ? "0-65535 (0: any free port)" : "1-65535"));
  endpoint.port = static_cast<uint16_t>(port);
  return endpoint;
}

namespace {

sockaddr_in socket_address(const UdpEndpoint& endpoint) {
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(endpoint.port);
  if (inet_pton(AF_INET, endpoint.host.c_str(), &address.sin_addr) != 1)
    throw Error(endpoint.url(), "not a dotted IPv4 address");
  return address;
}

int open_socket(const std::string& where) {
  const int descriptor = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (descriptor < 0) throw Error(where, system_error("cannot open a UDP socket"));
  return descriptor;
}

}  // namespace

UdpSocket UdpSocket::connect_to(const UdpEndpoint& destination) {
  const std::string where = destination.url();
  const sockaddr_in address = socket_address(destination);
  UdpSocket socket(open_socket(where), where);
  if (::connect(socket.descriptor_, reinterpret_cast<const sockaddr*>(&address), sizeof address) <
      0)
    throw Error(where, system_error("cannot address"));
  return socket;
}

UdpSocket UdpSocket::bind_to(const UdpEndpoint& local) {
  const std::string where = local.url();
  const sockaddr_in address = socket_address(local);
  UdpSocket socket(open_socket(where), where);
  // A live skin at 1 kHz must not lose datagrams while the reader is busy: ask for a large
  // receive buffer (the kernel caps it at net.core.rmem_max; failing to enlarge is harmless).
  const int buffer_bytes = 4 << 20;
  ::setsockopt(socket.descriptor_, SOL_SOCKET, SO_RCVBUF, &buffer_bytes, sizeof buffer_bytes);
  if (::bind(socket.descriptor_, reinterpret_cast<const sockaddr*>(&address), sizeof address) < 0)
    throw Error(where, system_error("cannot listen"));
  return socket;
}

UdpSocket::UdpSocket(UdpSocket&& other) noexcept
    : descriptor_(std::exchange(other.descriptor_, -1)), where_(std::move(other.where_)) {}

UdpSocket& UdpSocket::operator=(UdpSocket&& other) noexcept {
  if (this != &other) {
    if (descriptor_ >= 0) ::close(descriptor_);
    descriptor_ = std::exchange(other.descriptor_, -1);
    where_ = std::move(other.where_);
  }
  return *this;
}

UdpSocket::~UdpSocket() {
  if (descriptor_ >= 0) ::close(descriptor_);
}

bool UdpSocket::send(std::span<const uint8_t> datagram) {
  for (;;) {
    const ssize_t sent = ::send(descriptor_, datagram.data(), datagram.size(), 0);
    if (sent == static_cast<ssize_t>(datagram.size())) return true;
    if (sent >= 0) throw Error(where_, "datagram sent only in part");
    if (errno == EINTR) continue;
    // An ICMP "port unreachable" from an earlier datagram surfaces here on a connected socket.
    if (errno == ECONNREFUSED) return false;
    throw Error(where_, system_error("cannot send"));
  }
}

std::optional<size_t> UdpSocket::receive(std::span<uint8_t> buffer, double timeout_seconds) {
  pollfd request{descriptor_, POLLIN, 0};
  const int timeout_ms = static_cast<int>(std::ceil(std::max(0.0, timeout_seconds) * 1000.0));
  for (;;) {
    const int ready = ::poll(&request, 1, timeout_ms);
    if (ready == 0) return std::nullopt;
    if (ready < 0) {
      if (errno == EINTR) continue;
      throw Error(where_, system_error("cannot wait for datagrams"));
    }
    // MSG_TRUNC: the return value is the datagram's real length, so an oversized one is seen.
    const ssize_t size = ::recv(descriptor_, buffer.data(), buffer.size(), MSG_TRUNC);
    if (size >= 0) return static_cast<size_t>(size);
    if (errno == EINTR || errno == EAGAIN) continue;
    throw Error(where_, system_error("cannot receive"));
  }
}

uint16_t UdpSocket::local_port() const {
  sockaddr_in address{};
  socklen_t length = sizeof address;
  if (::getsockname(descriptor_, reinterpret_cast<sockaddr*>(&address), &length) < 0)
    throw Error(where_, system_error("cannot read the socket's address"));
  return ntohs(address.sin_port);
}

}  // namespace tactile
