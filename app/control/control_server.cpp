// Compiled as C++17: websocketpp 0.8 does not compile as C++20 (app/CMakeLists.txt).
#include "app/control/control_server.h"

#include <lo/lo.h>

#include <atomic>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>
#include <thread>
#include <websocketpp/config/asio_no_tls.hpp>
#include <websocketpp/server.hpp>

namespace gb {
namespace {

using WsServer = websocketpp::server<websocketpp::config::asio>;
using Handle = websocketpp::connection_hdl;

struct Query {
  std::string attribute, token;
};

// "HOST_INFO&token=abc" -> the attribute and the token.
Query parseQuery(const std::string& query) {
  Query q;
  size_t from = 0;
  while (from <= query.size()) {
    size_t to = query.find('&', from);
    if (to == std::string::npos) to = query.size();
    const std::string part = query.substr(from, to - from);
    if (part.rfind("token=", 0) == 0)
      q.token = part.substr(6);
    else if (!part.empty() && q.attribute.empty())
      q.attribute = part;
    from = to + 1;
  }
  return q;
}

void splitResource(const std::string& resource, std::string& path, Query& query) {
  const size_t mark = resource.find('?');
  path = resource.substr(0, mark);
  query = parseQuery(mark == std::string::npos ? std::string() : resource.substr(mark + 1));
}

// An OSC message of one value, serialised; empty when liblo cannot make it.
std::string oscPacket(const std::string& path, const OscValue& value) {
  lo_message message = lo_message_new();
  if (value.type == 'i')
    lo_message_add_int32(message, static_cast<int32_t>(value.number));
  else if (value.type == 's')
    lo_message_add_string(message, value.text.c_str());
  else
    lo_message_add_float(message, static_cast<float>(value.number));
  size_t size = 0;
  void* data = lo_message_serialise(message, path.c_str(), nullptr, &size);
  lo_message_free(message);
  if (!data) return {};
  std::string packet(static_cast<const char*>(data), size);
  free(data);
  return packet;
}

}  // namespace

bool isLoopback(const std::string& address) {
  return address == "localhost" || address == "::1" || address.rfind("127.", 0) == 0;
}

struct ControlServer::Impl {
  ControlServerOptions options;
  ControlRoutes routes;
  WsServer server;
  std::thread thread;
  lo_address osc = nullptr;
  struct Client {
    std::set<std::string> listens;
    std::map<std::string, OscValue> sent;
  };
  std::map<Handle, Client, std::owner_less<Handle>> clients;  // the server's thread only
  WsServer::timer_ptr timer;
  std::atomic<long> requests{0}, refused{0}, messages{0}, ignored{0}, clientCount{0};
  int port = 0;

  bool allowed(const Query& query) const { return options.token.empty() || query.token == options.token; }

  void answer(const WsServer::connection_ptr& con, const HttpAnswer& a) {
    ++requests;
    if (a.status >= 400) ++refused;
    con->set_status(static_cast<websocketpp::http::status_code::value>(a.status));
    con->replace_header("Content-Type", a.contentType);
    con->replace_header("Cache-Control", "no-store");
    con->set_body(a.body);
  }

  void onHttp(Handle handle) {
    const WsServer::connection_ptr con = server.get_con_from_hdl(handle);
    std::string path;
    Query query;
    splitResource(con->get_resource(), path, query);
    if (!allowed(query)) return answer(con, {401, "text/plain", "a token is needed: ?token=...\n"});
    const std::string method = con->get_request().get_method();
    if (method != "GET" && method != "HEAD") return answer(con, {405, "text/plain", "only GET is served\n"});
    try {
      answer(con, routes.get(path, query.attribute));
    } catch (const std::exception& e) {
      answer(con, {500, "text/plain", std::string("error: ") + e.what() + "\n"});
    }
  }

  bool onValidate(Handle handle) {
    const WsServer::connection_ptr con = server.get_con_from_hdl(handle);
    std::string path;
    Query query;
    splitResource(con->get_resource(), path, query);
    if (!allowed(query)) {
      con->set_status(websocketpp::http::status_code::unauthorized);
      return false;
    }
    if (clientCount >= ControlServer::kMostClients) {
      con->set_status(websocketpp::http::status_code::service_unavailable);
      return false;
    }
    return true;
  }

  void send(Handle handle, const std::string& path, const OscValue& value) {
    const std::string packet = oscPacket(path, value);
    if (packet.empty()) return;
    websocketpp::lib::error_code error;
    server.send(handle, packet.data(), packet.size(), websocketpp::frame::opcode::binary, error);
  }

  // LISTEN and IGNORE; anything else is counted and ignored.
  void onCommand(Handle handle, Client& client, const std::string& text) {
    const nlohmann::json command = nlohmann::json::parse(text, nullptr, false);
    if (command.is_discarded() || !command.is_object() || !command.contains("COMMAND") ||
        !command["COMMAND"].is_string() || !command.contains("DATA") || !command["DATA"].is_string()) {
      ++ignored;
      return;
    }
    const std::string name = command["COMMAND"], path = command["DATA"];
    if (name == "IGNORE") {
      client.listens.erase(path);
      client.sent.erase(path);
    } else if (name == "LISTEN" && client.listens.size() < ControlServer::kMostListens) {
      client.listens.insert(path);
      const auto values = routes.values();
      if (const auto v = values.find(path); v != values.end()) {  // the value now, then its changes
        send(handle, path, v->second);
        client.sent[path] = v->second;
      }
    } else {
      ++ignored;
    }
  }

  // An OSC message from a client goes to the show's OSC port, where UDP messages arrive.
  void onOsc(std::string packet) {
    int result = 0;
    lo_message message = lo_message_deserialise(packet.data(), packet.size(), &result);
    const char* path = message ? lo_get_path(packet.data(), static_cast<ssize_t>(packet.size())) : nullptr;
    if (!message || !path || !osc) {
      if (message) lo_message_free(message);
      ++ignored;
      return;
    }
    lo_send_message(osc, path, message);
    lo_message_free(message);
  }

  void onMessage(Handle handle, WsServer::message_ptr message) {
    const auto client = clients.find(handle);
    if (client == clients.end()) return;
    ++messages;
    if (message->get_opcode() == websocketpp::frame::opcode::text)
      onCommand(handle, client->second, message->get_payload());
    else
      onOsc(message->get_payload());
  }

  // The values that changed, to the clients that listen to them.
  void tick() {
    bool listening = false;
    for (const auto& [handle, client] : clients) listening = listening || !client.listens.empty();
    if (listening) {
      const auto values = routes.values();
      for (auto& [handle, client] : clients)
        for (const std::string& path : client.listens) {
          const auto v = values.find(path);
          if (v == values.end()) continue;
          const auto sent = client.sent.find(path);
          if (sent != client.sent.end() && sent->second == v->second) continue;
          send(handle, path, v->second);
          client.sent[path] = v->second;
        }
    }
    timer = server.set_timer(ControlServer::kListenPeriodMs, [this](const websocketpp::lib::error_code& error) {
      if (!error) tick();
    });
  }

  void listen() {
    server.clear_access_channels(websocketpp::log::alevel::all);
    server.clear_error_channels(websocketpp::log::elevel::all);
    server.init_asio();
    server.set_reuse_addr(true);
    server.set_max_message_size(ControlServer::kMostMessageBytes);
    server.set_max_http_body_size(ControlServer::kMostMessageBytes);
    server.set_http_handler([this](Handle h) { onHttp(h); });
    server.set_validate_handler([this](Handle h) { return onValidate(h); });
    server.set_open_handler([this](Handle h) {
      clients[h] = {};
      ++clientCount;
    });
    server.set_close_handler([this](Handle h) {
      if (clients.erase(h) > 0) --clientCount;
    });
    server.set_fail_handler([this](Handle h) {
      if (clients.erase(h) > 0) --clientCount;
    });
    server.set_message_handler([this](Handle h, WsServer::message_ptr m) { onMessage(h, m); });
    const std::string where = options.bind + ":" + std::to_string(options.port);
    boost::system::error_code error;
    const auto address = boost::asio::ip::make_address(options.bind, error);
    if (error) throw std::runtime_error("--control-bind " + options.bind + ": not an IP address");
    websocketpp::lib::error_code listenError;
    server.listen(boost::asio::ip::tcp::endpoint(address, static_cast<unsigned short>(options.port)), listenError);
    if (listenError)
      throw std::runtime_error("--control: cannot listen on " + where + " (" + listenError.message() +
                               "): is another program listening there?");
    server.start_accept(listenError);
    if (listenError) throw std::runtime_error("--control: cannot accept on " + where + ": " + listenError.message());
    boost::system::error_code endpointError;
    port = server.get_local_endpoint(endpointError).port();
  }
};

ControlServer::ControlServer(const ControlServerOptions& options, ControlRoutes routes)
    : impl_(std::make_unique<Impl>()) {
  if (options.port < 0 || options.port > 65535)
    throw std::runtime_error("--control " + std::to_string(options.port) + ": the port must be from 1 to 65535");
  if (!isLoopback(options.bind) && options.token.empty())
    throw std::runtime_error("--control-bind " + options.bind +
                             ": a bind other than loopback needs --control-token (every request then carries it)");
  impl_->options = options;
  impl_->routes = std::move(routes);
  if (options.oscPort > 0) impl_->osc = lo_address_new("127.0.0.1", std::to_string(options.oscPort).c_str());
  impl_->listen();
  impl_->tick();
  impl_->thread = std::thread([impl = impl_.get()] {
    try {
      impl->server.run();
    } catch (const std::exception&) {  // the show goes on without its control server
    }
  });
}

ControlServer::~ControlServer() {
  impl_->server.stop();
  if (impl_->thread.joinable()) impl_->thread.join();
  if (impl_->osc) lo_address_free(impl_->osc);
}

int ControlServer::port() const { return impl_->port; }

ControlServerCounts ControlServer::counts() const {
  return {impl_->requests, impl_->refused, impl_->messages, impl_->ignored, impl_->clientCount};
}

}  // namespace gb
