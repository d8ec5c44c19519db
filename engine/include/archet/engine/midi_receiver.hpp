#pragma once
// MIDI in through RtMidi, from the ALSA sequencer or JACK: a port of Archet's own that other
// programs and controllers connect to (a virtual port), or an existing port opened by a part
// of its name. RtMidi calls back on a thread of its own (JACK's process thread, for JACK):
// the callback only decodes and pushes into a lock-free ring, which the control thread drains
// at each round. Never on Archet's real-time thread.

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "archet/ipc/spsc_ring.hpp"
#include "archet/midi/midi_message.hpp"

class RtMidiIn;

namespace archet {

struct MidiInputOptions {
    std::string api = "alsa";  ///< alsa (the ALSA sequencer) or jack
    /// "virtual": a port named archet-midi:midi_in for others to connect to; otherwise the first
    /// input port whose name contains this text.
    std::string port = "virtual";
};

class MidiReceiver {
  public:
    /// Opens the port; throws InputError naming --midi (with the ports there are) when it
    /// cannot.
    explicit MidiReceiver(const MidiInputOptions& options);
    ~MidiReceiver();
    MidiReceiver(const MidiReceiver&) = delete;
    MidiReceiver& operator=(const MidiReceiver&) = delete;

    /// The messages that arrived since the last call, in order.
    std::vector<midi::MidiMessage> take();
    /// Messages lost because more than kQueue came between two calls.
    std::uint64_t dropped() const { return ring_.ring().dropped(); }
    /// What RtMidi reported since it opened (a JACK server gone, say), once.
    std::string take_problem();
    /// "ALSA port archet-midi:midi_in", for the engine's start-up line.
    const std::string& description() const { return description_; }

    static constexpr std::uint32_t kQueue = 4096;

  private:
    static void arrived(double, std::vector<unsigned char>* bytes, void* self);

    ipc::LocalRing<midi::MidiMessage> ring_{kQueue};
    std::unique_ptr<RtMidiIn> in_;
    std::string description_;
    std::mutex problem_mutex_;  ///< RtMidi's error callback and the control thread
    std::string problem_;
};

}  // namespace archet
