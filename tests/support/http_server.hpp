#pragma once
// A stock HTTP server for tests: Debian's lighttpd serving a folder on 127.0.0.1 at a free
// port (range requests included), with an access log, stopped by the destructor or stop().
#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace tellus::test {

class LocalHttpServer {
 public:
  // Starts serving `root`; nullopt (with the reason in `why`) when lighttpd is missing or does
  // not come up within 10 s.
  static std::optional<LocalHttpServer> start(const std::filesystem::path& root, std::string& why);
  // Python's http.server instead: it ignores Range headers (answers 200 with the whole file),
  // the server a store reader must refuse clearly. No access log.
  static std::optional<LocalHttpServer> startWithoutRanges(const std::filesystem::path& root,
                                                           std::string& why);
  LocalHttpServer(LocalHttpServer&& other) noexcept;
  LocalHttpServer& operator=(LocalHttpServer&&) = delete;
  ~LocalHttpServer();

  // http://127.0.0.1:PORT/relative
  std::string url(const std::string& relative) const;
  // Requests answered so far (lines of the access log; lighttpd writes them as it goes).
  int requests() const;
  // Kills the server (SIGKILL: a crash, not a goodbye) and waits for it.
  void kill();

 private:
  LocalHttpServer() = default;
  // Runs `argv` (the port already chosen) and waits until it accepts connections.
  static std::optional<LocalHttpServer> launch(LocalHttpServer server,
                                               const std::vector<std::string>& argv,
                                               std::string& why);
  pid_t pid_ = -1;
  int port_ = 0;
  std::filesystem::path folder_;  // config and logs
};

}  // namespace tellus::test
