#include "archet/engine/osc_receiver.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "archet/common/input_error.hpp"
#include "archet/engine/osc_packet.hpp"

namespace archet {

OscReceiver::OscReceiver(const std::string& host, int port) : port_(port) {
    const std::string where = "--osc " + std::to_string(port);
    if (port < 1 || port > 65535) throw InputError(where, "the port must be 1 to 65535");
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<std::uint16_t>(port));
    if (::inet_pton(AF_INET, host.c_str(), &address.sin_addr) != 1)
        throw InputError("--osc-host", "\"" + host + "\" is not an IPv4 address (e.g. 127.0.0.1)");
    socket_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    if (socket_ < 0) throw InputError(where, std::strerror(errno));
    if (::bind(socket_, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
        const std::string why = std::strerror(errno);
        ::close(socket_);
        throw InputError(where, "cannot listen on " + host + ":" + std::to_string(port) + " (" +
                                    why + "); pick another port");
    }
    thread_ = std::thread([this] { listen(); });
}

OscReceiver::~OscReceiver() {
    stop_ = true;
    thread_.join();
    ::close(socket_);
}

void OscReceiver::listen() {
    std::uint8_t packet[kMaxOscPacket + 1];
    while (!stop_) {
        pollfd ready{socket_, POLLIN, 0};
        if (::poll(&ready, 1, 50) <= 0) continue;  // wakes to see whether to stop
        const ssize_t size = ::recv(socket_, packet, sizeof packet, 0);
        if (size < 0) continue;
        Received received = decode_osc_packet(packet, static_cast<std::size_t>(size));
        const std::lock_guard lock(mutex_);
        if (queue_.size() >= kQueue) {
            ++dropped_;
            continue;
        }
        queue_.push_back(std::move(received));
    }
}

std::vector<OscReceiver::Received> OscReceiver::take() {
    const std::lock_guard lock(mutex_);
    std::vector<Received> out(std::make_move_iterator(queue_.begin()),
                              std::make_move_iterator(queue_.end()));
    queue_.clear();
    return out;
}

}  // namespace archet
