#pragma once
// A MIDI keyboard on JACK, written in the test: a client with one MIDI output whose process
// callback writes, in each cycle, the messages the test queued (through JACK's own lock-free
// ring buffer, as a real-time client must). Connected to every MIDI input whose name holds a
// given text, e.g. the engine's archet-midi:midi_in.

#include <jack/jack.h>
#include <jack/midiport.h>
#include <jack/ringbuffer.h>

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace archet::test {

class JackMidiKeyboard {
  public:
    JackMidiKeyboard() {
        client_ = jack_client_open("keyboard", JackNoStartServer, nullptr);
        if (!client_) throw std::runtime_error("cannot open a JACK client (is jackd running?)");
        out_ = jack_port_register(client_, "out", JACK_DEFAULT_MIDI_TYPE, JackPortIsOutput, 0);
        queue_ = jack_ringbuffer_create(1 << 16);
        jack_set_process_callback(client_, &JackMidiKeyboard::process, this);
        if (!out_ || jack_activate(client_) != 0)
            throw std::runtime_error("cannot start the JACK MIDI keyboard");
    }
    ~JackMidiKeyboard() {
        jack_deactivate(client_);
        jack_client_close(client_);
        jack_ringbuffer_free(queue_);
    }
    JackMidiKeyboard(const JackMidiKeyboard&) = delete;
    JackMidiKeyboard& operator=(const JackMidiKeyboard&) = delete;

    /// The MIDI inputs whose names contain `text`.
    std::vector<std::string> inputs(const std::string& text) const {
        std::vector<std::string> names;
        if (const char** ports =
                jack_get_ports(client_, nullptr, JACK_DEFAULT_MIDI_TYPE, JackPortIsInput)) {
            for (const char** p = ports; *p; ++p)
                if (std::string(*p).find(text) != std::string::npos) names.emplace_back(*p);
            jack_free(ports);
        }
        return names;
    }
    /// Connects the keyboard to the first input named like `text`; false when there is none.
    bool connect(const std::string& text) {
        const auto names = inputs(text);
        return !names.empty() && jack_connect(client_, jack_port_name(out_), names[0].c_str()) == 0;
    }
    /// Queues a message (1 to 3 bytes) for the next cycle; false when the queue is full.
    bool send(std::vector<std::uint8_t> bytes) {
        const std::uint8_t size = static_cast<std::uint8_t>(bytes.size());
        if (jack_ringbuffer_write_space(queue_) < 1u + size) return false;
        jack_ringbuffer_write(queue_, reinterpret_cast<const char*>(&size), 1);
        jack_ringbuffer_write(queue_, reinterpret_cast<const char*>(bytes.data()), size);
        return true;
    }
    bool note_on(int note, int velocity) { return send({0x90, byte(note), byte(velocity)}); }
    bool note_off(int note) { return send({0x80, byte(note), 0}); }
    bool control(int controller, int value) { return send({0xB0, byte(controller), byte(value)}); }

  private:
    static std::uint8_t byte(int v) { return static_cast<std::uint8_t>(v & 0x7F); }

    static int process(jack_nframes_t frames, void* self) {
        auto& k = *static_cast<JackMidiKeyboard*>(self);
        void* buffer = jack_port_get_buffer(k.out_, frames);
        jack_midi_clear_buffer(buffer);
        std::uint8_t size = 0, bytes[3];
        while (jack_ringbuffer_peek(k.queue_, reinterpret_cast<char*>(&size), 1) == 1 &&
               jack_ringbuffer_read_space(k.queue_) >= 1u + size &&
               jack_midi_max_event_size(buffer) >= size) {
            jack_ringbuffer_read_advance(k.queue_, 1);
            jack_ringbuffer_read(k.queue_, reinterpret_cast<char*>(bytes), size);
            if (jack_midi_event_write(buffer, 0, bytes, size) != 0) break;
        }
        return 0;
    }

    jack_client_t* client_ = nullptr;
    jack_port_t* out_ = nullptr;
    jack_ringbuffer_t* queue_ = nullptr;
};

}  // namespace archet::test
