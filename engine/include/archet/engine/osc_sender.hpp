#pragma once
// Sends what the bow and the string do to an OSC receiver (a visualiser in Max, Pd, a web
// page), from the control thread at a low rate: /archet/out/bow_force f (N, the bow's normal
// force), /archet/out/friction f (N, on the string) and /archet/out/energy f (J, stored in the
// model). UDP: a receiver that is not there loses nothing but the messages.

#include <string>

namespace archet {

class OscSender {
  public:
    /// `destination` is HOST:PORT; throws InputError naming --osc-send when it is not one.
    explicit OscSender(const std::string& destination);
    ~OscSender();
    OscSender(const OscSender&) = delete;
    OscSender& operator=(const OscSender&) = delete;

    void send(double bow_force, double friction, double energy);

  private:
    void* address_ = nullptr;  ///< liblo's lo_address
};

}  // namespace archet
