// Built as C++17: websocketpp 0.8.2 (Debian bookworm) declares constructors as template-ids,
// which C++20 rejects. Standalone asio (libasio-dev), no Boost.
#include "uavmot/foxglove/ws_server.hpp"

#include <atomic>
#include <cstring>
#include <deque>
#include <future>
#include <map>
#include <mutex>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>
#include <websocketpp/config/asio_no_tls.hpp>
#include <websocketpp/server.hpp>

#include "uavmot/core/error.hpp"

namespace uavmot::foxglove {
namespace {
using Server = websocketpp::server<websocketpp::config::asio>;
using Handle = websocketpp::connection_hdl;
using json = nlohmann::json;
constexpr const char* kSubprotocol = "foxglove.websocket.v1";
constexpr uint8_t kMessageDataOpcode = 1;
// The protocol's integers are little endian; publish() copies them as they are in memory.
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "publish() assumes a little-endian host");

json channel_json(uint32_t id, const WsChannel& c) {
  return {{"id", id}, {"topic", c.topic}, {"encoding", c.encoding}, {"schemaName", c.schema_name},
          {"schema", c.schema}, {"schemaEncoding", c.schema_encoding}};
}

// At most this much of a client's messages sits in websocketpp's own send buffer; the rest waits
// in the client's queue, so the bound of the queue is the bound of the client's memory.
constexpr size_t kSocketBufferBytes = 1u << 20;

struct Client {
  Server::connection_ptr connection;
  std::map<uint32_t, uint32_t> subscriptions;  // subscription id (the client's) -> channel id
  std::string peer;
  std::deque<std::string> queue;  // binary messages not yet handed to websocketpp
  size_t queued_bytes = 0;
};
}  // namespace

struct WsServer::Impl {
  WsServerOptions options;
  Server server;
  std::thread thread;
  mutable std::mutex mutex;  // clients and channels
  std::map<Handle, Client, std::owner_less<Handle>> clients;
  std::map<uint32_t, WsChannel> channels;
  uint32_t next_channel = 1;
  std::atomic<uint64_t> clients_seen{0}, sent{0}, dropped{0};
  uint16_t port = 0;
  // websocketpp's connections are not thread-safe (get_buffered_amount() reads what the network
  // thread writes: TSan), so only the network thread touches them; publish() only queues.
  std::atomic<bool> drain_posted{false};
  std::unique_ptr<asio::steady_timer> retry;  // network thread only

  void post_drain() {
    if (!drain_posted.exchange(true)) asio::post(server.get_io_service(), [this] { drain(); });
  }

  // Network thread: hands queued messages to websocketpp while each socket buffer has room; tries
  // again shortly while a slow client's queue is not empty.
  void drain() {
    drain_posted = false;
    bool waiting = false;
    {
      std::lock_guard lock(mutex);
      for (auto& [hdl, client] : clients) {
        while (!client.queue.empty() && client.connection->get_buffered_amount() < kSocketBufferBytes) {
          std::string message = std::move(client.queue.front());
          client.queue.pop_front();
          client.queued_bytes -= message.size();
          if (client.connection->send(message, websocketpp::frame::opcode::binary)) ++dropped;
          else ++sent;
        }
        waiting = waiting || !client.queue.empty();
      }
    }
    if (waiting) {
      if (!retry) retry = std::make_unique<asio::steady_timer>(server.get_io_service());
      retry->expires_after(std::chrono::milliseconds(2));
      retry->async_wait([this](const asio::error_code& ec) {
        if (!ec) post_drain();
      });
    }
  }

  void send_text(const Server::connection_ptr& con, const json& message) {
    con->send(message.dump(), websocketpp::frame::opcode::text);  // an error: the connection is closing
  }

  void status(const Server::connection_ptr& con, int level, const std::string& text) {
    send_text(con, {{"op", "status"}, {"level", level}, {"message", text}});
  }

  bool on_validate(Handle hdl) {
    auto con = server.get_con_from_hdl(hdl);
    for (const auto& p : con->get_requested_subprotocols()) {
      if (p == kSubprotocol) {
        con->select_subprotocol(kSubprotocol);
        return true;
      }
    }
    spdlog::warn("foxglove: refused {}: it does not offer the {} subprotocol", con->get_remote_endpoint(), kSubprotocol);
    return false;
  }

  void on_open(Handle hdl) {
    auto con = server.get_con_from_hdl(hdl);
    json advertise = {{"op", "advertise"}, {"channels", json::array()}};
    {
      std::lock_guard lock(mutex);
      Client& client = clients[hdl];
      client.connection = con;
      client.peer = con->get_remote_endpoint();
      for (const auto& [id, c] : channels) advertise["channels"].push_back(channel_json(id, c));
    }
    ++clients_seen;
    send_text(con, {{"op", "serverInfo"}, {"name", options.name}, {"capabilities", json::array()},
                    {"supportedEncodings", json::array()}, {"metadata", json::object()},
                    {"sessionId", std::to_string(std::chrono::system_clock::now().time_since_epoch().count())}});
    send_text(con, advertise);
    spdlog::info("foxglove: viewer {} connected", con->get_remote_endpoint());
  }

  void on_close(Handle hdl) {
    std::lock_guard lock(mutex);
    auto it = clients.find(hdl);
    if (it == clients.end()) return;
    spdlog::info("foxglove: viewer {} left", it->second.peer);
    clients.erase(it);
  }

  void on_message(Handle hdl, const Server::message_ptr& message) {
    auto con = server.get_con_from_hdl(hdl);
    if (message->get_opcode() != websocketpp::frame::opcode::text) {
      status(con, 1, "uavmot foxglove takes no client messages (binary opcode ignored)");
      return;
    }
    try {
      handle_request(hdl, con, json::parse(message->get_payload()));
    } catch (const std::exception& e) {
      status(con, 2, std::string("bad request: ") + e.what());
    }
  }

  void handle_request(Handle hdl, const Server::connection_ptr& con, const json& request) {
    const std::string op = request.at("op").get<std::string>();
    std::lock_guard lock(mutex);
    auto it = clients.find(hdl);
    if (it == clients.end()) return;
    if (op == "subscribe") {
      for (const auto& s : request.at("subscriptions")) {
        const auto channel = s.at("channelId").get<uint32_t>();
        if (!channels.count(channel)) {
          status(con, 2, fmt::format("subscribe: no channel {}", channel));
          continue;
        }
        it->second.subscriptions[s.at("id").get<uint32_t>()] = channel;
      }
    } else if (op == "unsubscribe") {
      for (const auto& id : request.at("subscriptionIds")) it->second.subscriptions.erase(id.get<uint32_t>());
    } else {
      status(con, 1, "uavmot foxglove does not support '" + op + "'");
    }
  }
};

WsServer::WsServer(WsServerOptions options) : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.options = std::move(options);
  const std::string where = fmt::format("{}:{}", s.options.address, s.options.port);
  websocketpp::lib::error_code ec;
  const auto address = asio::ip::make_address(s.options.address, ec);
  if (ec) throw InputError("--address '" + s.options.address + "' is not an IP address");
  s.server.clear_access_channels(websocketpp::log::alevel::all);
  s.server.clear_error_channels(websocketpp::log::elevel::all);
  s.server.init_asio(ec);
  if (ec) throw InputError("cannot start the WebSocket server: " + ec.message());
  s.server.set_reuse_addr(true);  // a restarted bridge gets its port back at once (TIME_WAIT)
  // No Nagle delay on small annotation messages (the socket is open once the TCP connection is).
  s.server.set_tcp_post_init_handler([&s](Handle h) {
    asio::error_code ignored;
    s.server.get_con_from_hdl(h)->get_socket().set_option(asio::ip::tcp::no_delay(true), ignored);
  });
  s.server.set_validate_handler([&s](Handle h) { return s.on_validate(h); });
  s.server.set_open_handler([&s](Handle h) { s.on_open(h); });
  s.server.set_close_handler([&s](Handle h) { s.on_close(h); });
  s.server.set_fail_handler([&s](Handle h) { s.on_close(h); });
  s.server.set_message_handler([&s](Handle h, Server::message_ptr m) { s.on_message(h, m); });
  s.server.listen(asio::ip::tcp::endpoint(address, s.options.port), ec);
  if (ec) throw InputError("cannot listen on " + where + ": " + ec.message());
  s.server.start_accept(ec);
  if (ec) throw InputError("cannot accept on " + where + ": " + ec.message());
  s.port = s.server.get_local_endpoint(ec).port();
  s.thread = std::thread([&s] { s.server.run(); });
}

WsServer::~WsServer() {
  Impl& s = *impl_;
  // On the network thread, like every other use of the acceptor and the connections.
  std::promise<void> closing;
  asio::post(s.server.get_io_service(), [&s, &closing] {
    websocketpp::lib::error_code ec;
    s.server.stop_listening(ec);
    if (s.retry) s.retry->cancel();
    std::lock_guard lock(s.mutex);
    for (auto& [hdl, client] : s.clients) client.connection->close(websocketpp::close::status::going_away, "uavmot foxglove stops", ec);
    closing.set_value();
  });
  closing.get_future().wait_for(std::chrono::seconds(2));
  // Give the close frames a moment to leave, then stop the network thread.
  for (int i = 0; i < 50 && counts().clients > 0; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  s.server.stop();
  if (s.thread.joinable()) s.thread.join();
}

uint16_t WsServer::port() const { return impl_->port; }

uint32_t WsServer::add_channel(const WsChannel& channel) {
  Impl& s = *impl_;
  std::lock_guard lock(s.mutex);
  const uint32_t id = s.next_channel++;
  s.channels[id] = channel;
  const json advertise = {{"op", "advertise"}, {"channels", json::array({channel_json(id, channel)})}};
  asio::post(s.server.get_io_service(), [&s, advertise] {
    std::lock_guard inner(s.mutex);
    for (auto& [hdl, client] : s.clients) s.send_text(client.connection, advertise);
  });
  return id;
}

bool WsServer::has_subscribers(uint32_t channel_id) const {
  std::lock_guard lock(impl_->mutex);
  for (const auto& [hdl, client] : impl_->clients) {
    for (const auto& [sub, channel] : client.subscriptions) {
      if (channel == channel_id) return true;
    }
  }
  return false;
}

void WsServer::publish(uint32_t channel_id, uint64_t timestamp_ns, const uint8_t* data, size_t size) {
  Impl& s = *impl_;
  std::string frame(1 + 4 + 8 + size, '\0');  // opcode, subscription id, timestamp (little endian), payload
  frame[0] = static_cast<char>(kMessageDataOpcode);
  std::memcpy(frame.data() + 5, &timestamp_ns, 8);
  if (size > 0) std::memcpy(frame.data() + 13, data, size);
  bool queued = false;
  {
    std::lock_guard lock(s.mutex);
    for (auto& [hdl, client] : s.clients) {
      for (const auto& [sub, channel] : client.subscriptions) {
        if (channel != channel_id) continue;
        // The bound: this client's queue. Over it, drop for this client, never wait.
        if (client.queued_bytes + frame.size() > s.options.client_buffer_bytes) {
          ++s.dropped;
          continue;
        }
        std::memcpy(frame.data() + 1, &sub, 4);
        client.queue.push_back(frame);
        client.queued_bytes += frame.size();
        queued = true;
      }
    }
  }
  if (queued) s.post_drain();
}

WsServerCounts WsServer::counts() const {
  const Impl& s = *impl_;
  WsServerCounts c;
  c.clients_seen = s.clients_seen;
  c.messages_sent = s.sent;
  c.messages_dropped = s.dropped;
  std::lock_guard lock(s.mutex);
  c.clients = s.clients.size();
  return c;
}

}  // namespace uavmot::foxglove
