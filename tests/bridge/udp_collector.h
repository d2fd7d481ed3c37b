// A UDP socket on an ephemeral loopback port that a background thread reads
// while the bridge runs, so no datagram is lost to a full socket buffer
// however long the stream is.
#pragma once

#include <arpa/inet.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace kelvin::testing {

class UdpCollector {
 public:
  UdpCollector() {
    fd_ = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    bound_ = ::bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof(a)) == 0;
    socklen_t len = sizeof(a);
    ::getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &len);
    port_ = ntohs(a.sin_port);
    reader_ = std::thread([this] { Read(); });
  }
  ~UdpCollector() {
    Stop();
    ::close(fd_);
  }
  UdpCollector(const UdpCollector&) = delete;
  UdpCollector& operator=(const UdpCollector&) = delete;

  bool bound() const { return bound_; }
  int port() const { return port_; }
  // Stops reading once every queued datagram is read; returns them in order.
  std::vector<std::string> Stop() {
    stop_.store(true);
    if (reader_.joinable()) reader_.join();
    std::lock_guard<std::mutex> lock(mutex_);
    return datagrams_;
  }

 private:
  void Read() {
    char buf[2048];
    pollfd p{fd_, POLLIN, 0};
    // After the stop request, reads on until the socket is empty.
    while (true) {
      const int ready = ::poll(&p, 1, 20);
      if (ready <= 0) {
        if (stop_.load()) return;
        continue;
      }
      const ssize_t n = ::recv(fd_, buf, sizeof(buf), 0);
      if (n < 0) return;
      std::lock_guard<std::mutex> lock(mutex_);
      datagrams_.emplace_back(buf, static_cast<std::size_t>(n));
    }
  }

  int fd_ = -1;
  int port_ = 0;
  bool bound_ = false;
  std::atomic<bool> stop_{false};
  std::mutex mutex_;
  std::vector<std::string> datagrams_;
  std::thread reader_;
};

}  // namespace kelvin::testing
