#pragma once
// The show's control server (live --control PORT): one TCP port for HTTP and WebSocket (websocketpp on Boost.Asio),
// on its own thread so that no client can stall the frame loop.
//
//   GET /                the OSCQuery namespace (oscquery_namespace.h); GET /PATH a node, /PATH?ATTRIBUTE one
//                        attribute of it, /?HOST_INFO the host's information; 404 for no such node
//   GET /control         the control page (control_page.h)
//   WebSocket            text: OSCQuery's {"COMMAND": "LISTEN" | "IGNORE", "DATA": "/PATH"}; the values of the
//                        paths listened to come back as binary OSC messages when they change. Binary: an OSC message,
//                        passed on to the show's OSC port as if it came over UDP (cues, parameters, presets)
//
// Bounded: at most kMostClients WebSockets, kMostListens paths each, messages of kMostMessageBytes; a request or
// message that breaks a rule is refused (4xx, or counted and ignored). A bind other than loopback needs a token,
// given as ?token=... on every request and on the WebSocket's URL.

// The transport knows nothing of the show: what it answers comes from ControlRoutes (control_routes.h). It is
// compiled as C++17 (websocketpp 0.8 does not compile as C++20), so this header stays within C++17.

#include <functional>
#include <map>
#include <memory>
#include <string>

namespace gb {

struct ControlServerOptions {
  int port = 0;                    // 0: a free port (port() says which)
  std::string bind = "127.0.0.1";  // the address listened on
  std::string token;               // required on every request when non-empty
  int oscPort = 0;                 // the show's OSC port (UDP), for HOST_INFO and the WebSocket's OSC
};

struct HttpAnswer {
  int status = 200;
  std::string contentType = "application/json";
  std::string body;
};

// A value sent to a LISTENing client: an OSC float ('f'), int ('i') or string ('s').
struct OscValue {
  char type = 'f';
  double number = 0;
  std::string text;
  bool operator==(const OscValue& o) const { return type == o.type && number == o.number && text == o.text; }
  bool operator!=(const OscValue& o) const { return !(*this == o); }
};

struct ControlRoutes {
  // The answer to GET PATH, with the query's attribute ("HOST_INFO", "VALUE", ...; empty for none).
  std::function<HttpAnswer(const std::string& path, const std::string& attribute)> get;
  // Every address that has a value, with it (called on the server's thread, at most every kListenPeriodMs).
  std::function<std::map<std::string, OscValue>()> values;
};

struct ControlServerCounts {
  long requests = 0;  // HTTP requests answered (any status)
  long refused = 0;   // HTTP requests answered with a 4xx
  long messages = 0;  // WebSocket messages taken
  long ignored = 0;   // WebSocket messages ignored (malformed, over a bound)
  long clients = 0;   // WebSockets open now
};

class ControlServer {
 public:
  static constexpr int kMostClients = 16;
  static constexpr int kMostListens = 256;
  static constexpr size_t kMostMessageBytes = 64 * 1024;

  // Listens and starts the server's thread. Throws std::runtime_error naming the address and port when it cannot
  // (a bad address, a port taken, a non-loopback bind without a token).
  static constexpr int kListenPeriodMs = 100;

  ControlServer(const ControlServerOptions& options, ControlRoutes routes);
  ~ControlServer();  // stops the thread; open clients are dropped
  ControlServer(const ControlServer&) = delete;
  ControlServer& operator=(const ControlServer&) = delete;

  [[nodiscard]] int port() const;
  [[nodiscard]] ControlServerCounts counts() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Whether an address is a loopback one (127.0.0.0/8, ::1, localhost).
bool isLoopback(const std::string& address);

}  // namespace gb
