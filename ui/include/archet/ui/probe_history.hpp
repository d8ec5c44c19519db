#pragma once
// The last few seconds of what the engine streamed, per probe and for the audio output: the
// scopes read windows of it at display rate. Plain C++ (no Qt), filled on the GUI thread.

#include <cstdint>
#include <string>
#include <vector>

#include "archet/ipc/segment_layout.hpp"

namespace archet::ui {

class ProbeHistory {
  public:
    static constexpr int kOutput = -1;  ///< channel of the audio output

    explicit ProbeHistory(std::size_t capacity = 48000 * 4);

    /// Forgets everything; `names` are the model's probe ids, in stream order.
    void reset(std::vector<std::string> names);
    void append(const ipc::ProbeFrame& frame);

    std::size_t size() const { return size_; }
    std::uint64_t newest_tick() const { return newest_tick_; }
    std::uint64_t frames_received() const { return received_; }
    const std::vector<std::string>& names() const { return names_; }
    /// The channel of a probe id, or −2 when the model has no such probe.
    int channel(const std::string& name) const;

    /// The newest `count` values of `channel` (fewer when not yet received), oldest first,
    /// ending `back` samples before the newest.
    std::vector<double> window(int channel, std::size_t count, std::size_t back = 0) const;
    /// The newest value of `channel` (0 before any).
    double latest(int channel) const;

  private:
    double at(int channel, std::size_t age) const;  ///< age 0 = newest

    std::size_t capacity_;
    std::vector<std::string> names_;
    std::vector<std::vector<double>> channels_;  ///< probes, then the output
    std::size_t head_ = 0, size_ = 0;
    std::uint64_t newest_tick_ = 0, received_ = 0;
};

}  // namespace archet::ui
