#include "support/misbehaving_http_server.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <regex>

#include <fmt/format.h>

namespace tellus::test {
namespace {

// Reads one request's head (up to the blank line); false when the peer closed or we stop.
bool readRequest(int connection, const std::atomic<bool>& stop, std::string& head) {
  head.clear();
  char buffer[4096];
  while (head.find("\r\n\r\n") == std::string::npos) {
    pollfd p{connection, POLLIN, 0};
    const int ready = ::poll(&p, 1, 100);
    if (stop) return false;
    if (ready <= 0) continue;
    const ssize_t n = ::recv(connection, buffer, sizeof(buffer), 0);
    if (n <= 0) return false;
    head.append(buffer, std::size_t(n));
  }
  return true;
}

bool sendAll(int connection, const std::string& bytes) {
  std::size_t sent = 0;
  while (sent < bytes.size()) {
    const ssize_t n = ::send(connection, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) return false;
    sent += std::size_t(n);
  }
  return true;
}

}  // namespace

std::unique_ptr<MisbehavingHttpServer> MisbehavingHttpServer::start(Misbehaviour behaviour,
                                                                    std::filesystem::path file,
                                                                    std::uint64_t stallFrom,
                                                                    std::uint64_t stallTo) {
  std::unique_ptr<MisbehavingHttpServer> server(new MisbehavingHttpServer());
  server->behaviour_ = behaviour;
  server->stallFrom_ = stallFrom;
  server->stallTo_ = stallTo;
  if (!file.empty()) {
    std::ifstream in(file, std::ios::binary);
    server->fileBytes_.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  server->listener_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (server->listener_ < 0) return nullptr;
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = 0;
  socklen_t length = sizeof(address);
  if (::bind(server->listener_, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0 ||
      ::listen(server->listener_, 64) != 0 ||
      ::getsockname(server->listener_, reinterpret_cast<sockaddr*>(&address), &length) != 0) {
    ::close(server->listener_);
    return nullptr;
  }
  server->port_ = ntohs(address.sin_port);
  server->acceptor_ = std::thread([s = server.get()] { s->acceptLoop(); });
  return server;
}

MisbehavingHttpServer::~MisbehavingHttpServer() {
  stop_ = true;
  if (acceptor_.joinable()) acceptor_.join();
  std::lock_guard lock(threadsMutex_);
  for (std::thread& t : connections_) t.join();
  if (listener_ >= 0) ::close(listener_);
}

std::string MisbehavingHttpServer::url(const std::string& name) const {
  return fmt::format("http://127.0.0.1:{}/{}", port_, name);
}

bool MisbehavingHttpServer::waitForStop(int ms) const {
  const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(ms);
  while (std::chrono::steady_clock::now() < until) {
    if (stop_) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return stop_;
}

void MisbehavingHttpServer::acceptLoop() {
  while (!stop_) {
    pollfd p{listener_, POLLIN, 0};
    if (::poll(&p, 1, 100) <= 0) continue;
    const int connection = ::accept4(listener_, nullptr, nullptr, SOCK_CLOEXEC);
    if (connection < 0) continue;
    std::lock_guard lock(threadsMutex_);
    connections_.emplace_back([this, connection] {
      serve(connection);
      ::close(connection);
    });
  }
}

void MisbehavingHttpServer::serve(int connection) {
  static const std::regex range(R"(Range: *bytes=(\d+)-(\d+))", std::regex::icase);
  std::string head;
  while (readRequest(connection, stop_, head)) {
    ++requests_;
    std::smatch match;
    std::uint64_t first = 0, last = 0;
    if (std::regex_search(head, match, range)) {
      first = std::stoull(match[1].str());
      last = std::stoull(match[2].str());
    }
    const std::uint64_t size = fileBytes_.empty() ? 1000000 : fileBytes_.size();
    const std::string partialHead = fmt::format(
        "HTTP/1.1 206 Partial Content\r\nContent-Range: bytes {}-{}/{}\r\nContent-Length: {}\r\n\r\n",
        first, last, size, last - first + 1);
    switch (behaviour_) {
      case Misbehaviour::Silent:
        waitForStop(1 << 30);
        return;
      case Misbehaviour::RedirectLoop:
        if (!sendAll(connection, "HTTP/1.1 302 Found\r\nLocation: /loop\r\nContent-Length: 0\r\n\r\n")) return;
        continue;
      case Misbehaviour::HeadersThenSilence:
        sendAll(connection, partialHead);
        waitForStop(1 << 30);
        return;
      case Misbehaviour::Trickle:
        if (!sendAll(connection, partialHead)) return;
        for (std::uint64_t k = first; k <= last; ++k) {
          if (waitForStop(1000) || !sendAll(connection, std::string(1, 'x'))) return;
        }
        continue;
      case Misbehaviour::StallOnRange:
        if ((first >= stallFrom_ && first < stallTo_) || last >= fileBytes_.size() || first > last) {
          waitForStop(1 << 30);
          return;
        }
        if (!sendAll(connection, partialHead + fileBytes_.substr(first, last - first + 1))) return;
        continue;
    }
  }
}

}  // namespace tellus::test
