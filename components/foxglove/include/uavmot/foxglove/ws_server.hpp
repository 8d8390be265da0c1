#pragma once
// A server of the Foxglove WebSocket protocol (subprotocol "foxglove.websocket.v1",
// github.com/foxglove/ws-protocol): advertises channels, takes subscriptions, sends each
// subscriber the messages of its channels (binary opcode 1). Any number of clients.
// publish() never waits for the network, so a slow viewer cannot slow its caller: each client
// has a bounded queue (`client_buffer_bytes`) that the network thread empties into its socket
// (at most 1 MiB in websocketpp's buffer at a time); a message that does not fit is dropped for
// that client only, and counted. One thread runs the network and alone touches the connections.
// No DDS, no uavmot types: `uavmot foxglove` feeds it.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace uavmot::foxglove {

struct WsChannel {
  std::string topic;
  std::string encoding;         // message encoding: "cdr"
  std::string schema_name;      // "uavmot::msg::TrackList", "foxglove::ImageAnnotations"
  std::string schema;           // the schema text (self-contained OMG IDL)
  std::string schema_encoding;  // "omgidl"
};

struct WsServerOptions {
  std::string address = "127.0.0.1";  // localhost only unless asked
  uint16_t port = 8765;               // 0: any free port (tests)
  size_t client_buffer_bytes = 32u << 20;
  std::string name = "uavmot";        // the serverInfo name viewers show
};

struct WsServerCounts {
  uint64_t clients_seen = 0;     // connections accepted since start
  uint64_t clients = 0;          // connected now
  uint64_t messages_sent = 0;    // handed to a client's socket
  uint64_t messages_dropped = 0; // not sent: that client's queue was full
};

class WsServer {
 public:
  // Listening when it returns. Throws InputError when the address is not an IP address or the
  // port cannot be bound (in use, no permission), naming both and the system's reason.
  explicit WsServer(WsServerOptions options);
  ~WsServer();  // closes every connection, stops the network thread
  WsServer(const WsServer&) = delete;
  WsServer& operator=(const WsServer&) = delete;

  uint16_t port() const;  // the bound port (the chosen one when asked for 0)
  // Adds a channel and advertises it to every client, now and later; returns its id (from 1).
  uint32_t add_channel(const WsChannel& channel);
  // True when some client subscribes to the channel: callers skip conversions nobody wants.
  bool has_subscribers(uint32_t channel_id) const;
  // Sends the message to every subscriber of the channel whose queue has room. Thread-safe.
  void publish(uint32_t channel_id, uint64_t timestamp_ns, const uint8_t* data, size_t size);
  WsServerCounts counts() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace uavmot::foxglove
