#pragma once
// An HTTP server on 127.0.0.1 that misbehaves on purpose, in the test's own process: what a
// dead, looping or trickling server does to a client, for the tests that every command gives
// up on it in time (tellus/tiles/http_byte_source.hpp). Stopped, with every connection, by the
// destructor.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace tellus::test {

enum class Misbehaviour {
  Silent,              // accepts, reads the request, never answers
  RedirectLoop,        // answers every request with a redirect to itself
  HeadersThenSilence,  // a 206's headers, then no body
  Trickle,             // a 206's headers, then one byte a second
  StallOnRange,        // serves the file's ranges, but never answers one starting in
                       // [stallFrom, stallTo) (a store's tiles, say, after its index came)
};

class MisbehavingHttpServer {
 public:
  // nullptr when no port could be bound. `file` is what StallOnRange serves.
  static std::unique_ptr<MisbehavingHttpServer> start(Misbehaviour behaviour,
                                                      std::filesystem::path file = {},
                                                      std::uint64_t stallFrom = 0,
                                                      std::uint64_t stallTo = 0);
  ~MisbehavingHttpServer();
  MisbehavingHttpServer(const MisbehavingHttpServer&) = delete;
  MisbehavingHttpServer& operator=(const MisbehavingHttpServer&) = delete;

  // http://127.0.0.1:PORT/name
  std::string url(const std::string& name) const;
  // Requests received so far (every request line read, redirects included).
  int requests() const { return requests_.load(); }

 private:
  MisbehavingHttpServer() = default;
  void acceptLoop();
  void serve(int connection);
  // Waits up to `ms` for `stop_`; true when stopping.
  bool waitForStop(int ms) const;

  Misbehaviour behaviour_ = Misbehaviour::Silent;
  std::string fileBytes_;
  std::uint64_t stallFrom_ = 0, stallTo_ = 0;
  int listener_ = -1;
  int port_ = 0;
  std::atomic<bool> stop_{false};
  std::atomic<int> requests_{0};
  std::thread acceptor_;
  std::mutex threadsMutex_;
  std::vector<std::thread> connections_;
};

}  // namespace tellus::test
