#include "support/http_server.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <thread>

#include <fmt/format.h>

#include "support/test_support.hpp"

namespace tellus::test {
namespace fs = std::filesystem;
namespace {

// A port the kernel says is free now (bound to 0, then released).
int freePort() {
  const int s = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = 0;
  socklen_t length = sizeof(address);
  int port = 0;
  if (::bind(s, reinterpret_cast<sockaddr*>(&address), sizeof(address)) == 0 &&
      ::getsockname(s, reinterpret_cast<sockaddr*>(&address), &length) == 0) {
    port = ntohs(address.sin_port);
  }
  ::close(s);
  return port;
}

bool accepts(int port) {
  const int s = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = htons(std::uint16_t(port));
  const bool ok = ::connect(s, reinterpret_cast<sockaddr*>(&address), sizeof(address)) == 0;
  ::close(s);
  return ok;
}

const char* lighttpdPath() {
  for (const char* path : {"/usr/sbin/lighttpd", "/usr/bin/lighttpd"}) {
    if (::access(path, X_OK) == 0) return path;
  }
  return nullptr;
}

}  // namespace

std::optional<LocalHttpServer> LocalHttpServer::start(const fs::path& root, std::string& why) {
  const char* binary = lighttpdPath();
  if (!binary) {
    why = "lighttpd is not installed (scripts/install-deps.sh installs it)";
    return std::nullopt;
  }
  static int serial = 0;
  LocalHttpServer server;
  server.folder_ = testOutputDir() / fmt::format("lighttpd-{}-{}", ::getpid(), serial++);
  fs::remove_all(server.folder_);
  fs::create_directories(server.folder_);
  server.port_ = freePort();
  {
    std::ofstream conf(server.folder_ / "lighttpd.conf");
    conf << fmt::format(
        "server.document-root = \"{}\"\nserver.bind = \"127.0.0.1\"\nserver.port = {}\n"
        "server.errorlog = \"{}\"\nserver.modules = (\"mod_accesslog\")\n"
        "accesslog.filename = \"{}\"\n"
        "mimetype.assign = (\".tstore\" => \"application/octet-stream\", "
        "\".json\" => \"application/json\", \".terrain\" => \"application/vnd.quantized-mesh\")\n",
        fs::absolute(root).string(), server.port_, (server.folder_ / "error.log").string(),
        (server.folder_ / "access.log").string());
  }
  const std::vector<std::string> argv{binary, "-D", "-f", (server.folder_ / "lighttpd.conf").string()};
  return launch(std::move(server), argv, why);
}

std::optional<LocalHttpServer> LocalHttpServer::startWithoutRanges(const fs::path& root,
                                                                  std::string& why) {
  static int serial = 0;
  LocalHttpServer server;
  server.folder_ = testOutputDir() / fmt::format("python-http-{}-{}", ::getpid(), serial++);
  fs::create_directories(server.folder_);
  server.port_ = freePort();
  const std::vector<std::string> argv{"/usr/bin/python3", "-m", "http.server",
                                      std::to_string(server.port_), "--bind", "127.0.0.1",
                                      "--directory", fs::absolute(root).string()};
  return launch(std::move(server), argv, why);
}

std::optional<LocalHttpServer> LocalHttpServer::launch(LocalHttpServer server,
                                                       const std::vector<std::string>& argv,
                                                       std::string& why) {
  std::vector<char*> args;
  for (const std::string& arg : argv) args.push_back(const_cast<char*>(arg.c_str()));
  args.push_back(nullptr);
  const std::string log = (server.folder_ / "server.log").string();
  server.pid_ = ::fork();
  if (server.pid_ == 0) {
    std::FILE* out = std::freopen(log.c_str(), "w", stdout);
    std::FILE* err = std::freopen(log.c_str(), "a", stderr);
    (void)out;
    (void)err;
    ::execv(args[0], args.data());
    ::_exit(127);
  }
  for (int i = 0; i < 200; ++i) {
    if (accepts(server.port_)) return server;
    int status = 0;
    if (::waitpid(server.pid_, &status, WNOHANG) == server.pid_) {
      server.pid_ = -1;
      why = fmt::format("{} exited at start (see {})", argv[0], log);
      return std::nullopt;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  why = fmt::format("{} did not accept connections within 10 s", argv[0]);
  return std::nullopt;  // the destructor kills it
}

LocalHttpServer::LocalHttpServer(LocalHttpServer&& other) noexcept
    : pid_(other.pid_), port_(other.port_), folder_(std::move(other.folder_)) {
  other.pid_ = -1;
}

LocalHttpServer::~LocalHttpServer() { kill(); }

std::string LocalHttpServer::url(const std::string& relative) const {
  return fmt::format("http://127.0.0.1:{}/{}", port_, relative);
}

int LocalHttpServer::requests() const {
  std::ifstream log(folder_ / "access.log");
  int lines = 0;
  for (std::string line; std::getline(log, line);) ++lines;
  return lines;
}

void LocalHttpServer::kill() {
  if (pid_ <= 0) return;
  ::kill(pid_, SIGKILL);
  int status = 0;
  ::waitpid(pid_, &status, 0);
  pid_ = -1;
}

}  // namespace tellus::test
