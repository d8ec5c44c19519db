#include "archet/engine/osc_sender.hpp"

#include <lo/lo.h>
#include <netdb.h>
#include <sys/socket.h>

#include <charconv>

#include "archet/common/input_error.hpp"
#include "archet/common/printable_text.hpp"

namespace archet {

OscSender::OscSender(const std::string& destination) {
    const auto colon = destination.rfind(':');
    int port = 0;
    const char* end = destination.data() + destination.size();
    const bool parsed = colon != std::string::npos && colon > 0 &&
                        std::from_chars(destination.data() + colon + 1, end, port).ptr == end;
    if (!parsed || port < 1 || port > 65535)
        throw InputError("--osc-send",
                         quoted_text(destination) + " is not HOST:PORT (e.g. localhost:9001)");
    const std::string host = destination.substr(0, colon);
    // Resolved once here: a name that does not resolve would make every send wait on it.
    addrinfo hints{};
    hints.ai_family = AF_UNSPEC, hints.ai_socktype = SOCK_DGRAM;
    addrinfo* found = nullptr;
    if (::getaddrinfo(host.c_str(), nullptr, &hints, &found) != 0 || !found)
        throw InputError("--osc-send", "cannot find the host " + quoted_text(host));
    char numeric[NI_MAXHOST];
    const int named = ::getnameinfo(found->ai_addr, found->ai_addrlen, numeric, sizeof numeric,
                                    nullptr, 0, NI_NUMERICHOST);
    ::freeaddrinfo(found);
    if (named != 0) throw InputError("--osc-send", "cannot find the host " + quoted_text(host));
    address_ = lo_address_new(numeric, std::to_string(port).c_str());
    if (!address_) throw InputError("--osc-send", "cannot send to " + quoted_text(destination));
}

OscSender::~OscSender() {
    lo_address_free(static_cast<lo_address>(address_));
}

void OscSender::send(double bow_force, double friction, double energy) {
    const auto to = static_cast<lo_address>(address_);
    lo_send(to, "/archet/out/bow_force", "f", static_cast<float>(bow_force));
    lo_send(to, "/archet/out/friction", "f", static_cast<float>(friction));
    lo_send(to, "/archet/out/energy", "f", static_cast<float>(energy));
}

}  // namespace archet
