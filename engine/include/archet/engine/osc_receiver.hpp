#pragma once
// Listens for OSC on a UDP port: a thread of its own reads each datagram, decodes it
// (osc_packet.hpp) and queues the command, or the reason it was refused, for the control
// thread to take. Bound to the loopback address unless told otherwise: a port open to the
// network is the player's choice. Never on the real-time thread.

#include <atomic>
#include <deque>
#include <mutex>
#include <string>
#include <thread>
#include <variant>
#include <vector>

#include "archet/ipc/osc_command.hpp"

namespace archet {

class OscReceiver {
  public:
    /// What arrived: a command, or why a message was refused.
    using Received = std::variant<ipc::OscCommand, std::string>;

    /// Binds `host`:`port` (an IPv4 address; 0.0.0.0 for every interface) and starts
    /// listening. Throws InputError naming --osc when the port cannot be had.
    OscReceiver(const std::string& host, int port);
    ~OscReceiver();
    OscReceiver(const OscReceiver&) = delete;
    OscReceiver& operator=(const OscReceiver&) = delete;

    /// What arrived since the last call, in order. At most kQueue are kept between calls;
    /// beyond that the newest are dropped, and counted.
    std::vector<Received> take();
    std::uint64_t dropped() const { return dropped_.load(); }
    int port() const { return port_; }

    static constexpr std::size_t kQueue = 4096;

  private:
    void listen();

    int socket_ = -1;
    int port_ = 0;
    std::atomic<bool> stop_{false};
    std::atomic<std::uint64_t> dropped_{0};
    std::mutex mutex_;
    std::deque<Received> queue_;
    std::thread thread_;
};

}  // namespace archet
