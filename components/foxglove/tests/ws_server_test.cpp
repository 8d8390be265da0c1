// The Foxglove WebSocket server, spoken to over a real TCP socket by a minimal client written
// here (handshake, masked client frames, unmasked server frames): what it advertises, what it
// sends a subscriber, that a viewer who stops reading loses messages while publish() goes on at
// full speed, and the errors for a port in use or a bad address.

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <thread>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "uavmot/core/error.hpp"
#include "uavmot/foxglove/ws_server.hpp"

namespace uavmot::foxglove {
namespace {
using json = nlohmann::json;

class TestClient {
 public:
  TestClient(uint16_t port, const std::string& subprotocol = "foxglove.websocket.v1", int receive_buffer = 0) {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    if (receive_buffer > 0) ::setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &receive_buffer, sizeof receive_buffer);
    timeval tv{5, 0};
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(port);
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::connect(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) throw std::runtime_error("connect failed");
    std::string request = "GET / HTTP/1.1\r\nHost: localhost\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
                          "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n";
    if (!subprotocol.empty()) request += "Sec-WebSocket-Protocol: " + subprotocol + "\r\n";
    request += "\r\n";
    send_all(request.data(), request.size());
    while (response_.find("\r\n\r\n") == std::string::npos) {
      char c;
      if (::recv(fd_, &c, 1, 0) != 1) break;
      response_ += c;
    }
  }
  ~TestClient() { ::close(fd_); }

  const std::string& handshake() const { return response_; }

  // One whole message: {opcode, payload}.
  std::pair<int, std::string> receive() {
    uint8_t head[2];
    read_exact(head, 2);
    uint64_t length = head[1] & 0x7f;
    if (length == 126) {
      uint8_t b[2];
      read_exact(b, 2);
      length = (uint64_t{b[0]} << 8) | b[1];
    } else if (length == 127) {
      uint8_t b[8];
      read_exact(b, 8);
      length = 0;
      for (uint8_t x : b) length = (length << 8) | x;
    }
    std::string payload(length, '\0');
    read_exact(payload.data(), length);
    return {head[0] & 0x0f, payload};
  }
  json receive_json() {
    auto [opcode, payload] = receive();
    EXPECT_EQ(opcode, 1);
    return json::parse(payload);
  }

  void send_text(const std::string& text) {
    std::vector<uint8_t> frame = {0x81};
    if (text.size() < 126) {
      frame.push_back(static_cast<uint8_t>(0x80 | text.size()));
    } else {
      frame.push_back(0x80 | 126);
      frame.push_back(static_cast<uint8_t>(text.size() >> 8));
      frame.push_back(static_cast<uint8_t>(text.size()));
    }
    const uint8_t mask[4] = {1, 2, 3, 4};
    frame.insert(frame.end(), mask, mask + 4);
    for (size_t i = 0; i < text.size(); ++i) frame.push_back(static_cast<uint8_t>(text[i]) ^ mask[i % 4]);
    send_all(frame.data(), frame.size());
  }

 private:
  void send_all(const void* data, size_t size) {
    ASSERT_EQ(::send(fd_, data, size, MSG_NOSIGNAL), static_cast<ssize_t>(size));
  }
  void read_exact(void* out, size_t size) {
    auto* p = static_cast<char*>(out);
    while (size > 0) {
      const ssize_t n = ::recv(fd_, p, size, 0);
      if (n <= 0) throw std::runtime_error("connection closed or timed out");
      p += n;
      size -= static_cast<size_t>(n);
    }
  }
  int fd_ = -1;
  std::string response_;
};

WsChannel channel(const std::string& topic) { return {topic, "cdr", "foxglove::ImageAnnotations", "struct X {};", "omgidl"}; }

template <class Pred>
bool eventually(Pred pred) {
  for (int i = 0; i < 500 && !pred(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  return pred();
}

TEST(WsServer, AdvertisesChannelsAndSendsSubscribedMessages) {
  WsServer server({.address = "127.0.0.1", .port = 0});
  const uint32_t tracks = server.add_channel(channel("uavmot/foxglove/tracks"));
  const uint32_t image = server.add_channel(channel("uavmot/foxglove/image"));
  TestClient client(server.port());
  EXPECT_NE(client.handshake().find(" 101 "), std::string::npos) << client.handshake();
  EXPECT_NE(client.handshake().find("Sec-WebSocket-Protocol: foxglove.websocket.v1"), std::string::npos);

  const json info = client.receive_json();
  EXPECT_EQ(info["op"], "serverInfo");
  EXPECT_EQ(info["name"], "uavmot");
  const json advertise = client.receive_json();
  ASSERT_EQ(advertise["op"], "advertise");
  ASSERT_EQ(advertise["channels"].size(), 2u);
  EXPECT_EQ(advertise["channels"][0]["id"], tracks);
  EXPECT_EQ(advertise["channels"][0]["topic"], "uavmot/foxglove/tracks");
  EXPECT_EQ(advertise["channels"][0]["schemaEncoding"], "omgidl");
  EXPECT_EQ(advertise["channels"][0]["schemaName"], "foxglove::ImageAnnotations");

  EXPECT_FALSE(server.has_subscribers(tracks));
  client.send_text(json{{"op", "subscribe"}, {"subscriptions", {{{"id", 42}, {"channelId", tracks}}}}}.dump());
  ASSERT_TRUE(eventually([&] { return server.has_subscribers(tracks); }));
  EXPECT_FALSE(server.has_subscribers(image));
  const std::vector<uint8_t> payload = {0, 1, 0, 0, 9, 8, 7};
  server.publish(image, 5, payload.data(), payload.size());  // nobody subscribed: not sent
  server.publish(tracks, 0x0102030405060708ull, payload.data(), payload.size());
  const auto [opcode, message] = client.receive();
  ASSERT_EQ(opcode, 2);  // binary
  ASSERT_EQ(message.size(), 13u + payload.size());
  EXPECT_EQ(message[0], 1);  // MESSAGE_DATA
  uint32_t subscription;
  uint64_t timestamp;
  std::memcpy(&subscription, message.data() + 1, 4);
  std::memcpy(&timestamp, message.data() + 5, 8);
  EXPECT_EQ(subscription, 42u);
  EXPECT_EQ(timestamp, 0x0102030405060708ull);
  EXPECT_EQ(std::string(message.data() + 13, payload.size()), std::string(payload.begin(), payload.end()));

  // A channel added later is advertised to clients already connected.
  server.add_channel(channel("uavmot/health"));
  const json later = client.receive_json();
  EXPECT_EQ(later["op"], "advertise");
  EXPECT_EQ(later["channels"][0]["topic"], "uavmot/health");

  client.send_text(R"({"op": "subscribe", "subscriptions": [{"id": 1, "channelId": 99}]})");
  const json status = client.receive_json();
  EXPECT_EQ(status["op"], "status");
  EXPECT_EQ(status["level"], 2);
  client.send_text(json{{"op", "unsubscribe"}, {"subscriptionIds", {42}}}.dump());
  ASSERT_TRUE(eventually([&] { return !server.has_subscribers(tracks); }));
  EXPECT_EQ(server.counts().messages_sent, 1u);
  EXPECT_EQ(server.counts().clients, 1u);
}

TEST(WsServer, RefusesClientsWithoutTheFoxgloveSubprotocol) {
  WsServer server({.address = "127.0.0.1", .port = 0});
  TestClient client(server.port(), "");
  EXPECT_EQ(client.handshake().find(" 101 "), std::string::npos) << client.handshake();
  EXPECT_EQ(server.counts().clients_seen, 0u);
}

TEST(WsServer, ASlowViewerLosesMessagesAndNeverSlowsPublish) {
  const size_t buffer = 1u << 20;
  WsServer server({.address = "127.0.0.1", .port = 0, .client_buffer_bytes = buffer});
  const uint32_t image = server.add_channel(channel("uavmot/foxglove/image"));
  TestClient slow(server.port(), "foxglove.websocket.v1", 4096);  // reads nothing after subscribing
  slow.receive_json();
  slow.receive_json();
  slow.send_text(json{{"op", "subscribe"}, {"subscriptions", {{{"id", 0}, {"channelId", image}}}}}.dump());
  ASSERT_TRUE(eventually([&] { return server.has_subscribers(image); }));

  const std::vector<uint8_t> frame(256 * 1024, 0x55);
  const int frames = 400;  // 100 MiB: far more than the socket and the 1 MiB queue hold
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < frames; ++i) server.publish(image, static_cast<uint64_t>(i), frame.data(), frame.size());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto counts = server.counts();
  EXPECT_GT(counts.messages_dropped, static_cast<uint64_t>(frames / 2));
  EXPECT_LE(counts.messages_sent + counts.messages_dropped, static_cast<uint64_t>(frames));  // the rest still queued
  // 400 x 256 KiB copied once each: milliseconds (2 s under TSan on a loaded machine); waiting for
  // the viewer, who never reads, would never end.
  EXPECT_LT(seconds, 10.0);
}

TEST(WsServer, PortInUseAndBadAddressAreClearErrors) {
  WsServer first({.address = "127.0.0.1", .port = 0});
  const uint16_t port = first.port();
  try {
    WsServer second({.address = "127.0.0.1", .port = port});
    FAIL() << "a second server on port " << port << " started";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("cannot listen on 127.0.0.1:" + std::to_string(port)), std::string::npos) << message;
    EXPECT_NE(message.find("in use"), std::string::npos) << message;
  }
  EXPECT_THROW(WsServer({.address = "localhost:80", .port = 0}), InputError);
}

}  // namespace
}  // namespace uavmot::foxglove
