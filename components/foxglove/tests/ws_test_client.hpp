#pragma once
// A minimal Foxglove WebSocket client over a real TCP socket (handshake, masked client frames,
// unmasked server frames), for tests that talk to the server or to `uavmot foxglove`.

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace uavmot::foxglove {

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
  nlohmann::json receive_json() {
    auto [opcode, payload] = receive();
    EXPECT_EQ(opcode, 1);
    return nlohmann::json::parse(payload);
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

// Polls `pred` for up to 5 s.
template <class Pred>
bool eventually(Pred pred) {
  for (int i = 0; i < 500 && !pred(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  return pred();
}

}  // namespace uavmot::foxglove
