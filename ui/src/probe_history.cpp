#include "archet/ui/probe_history.hpp"

#include <algorithm>

namespace archet::ui {

ProbeHistory::ProbeHistory(std::size_t capacity) : capacity_(std::max<std::size_t>(capacity, 2)) {
    reset({});
}

void ProbeHistory::reset(std::vector<std::string> names) {
    names_ = std::move(names);
    if (names_.size() > ipc::kMaxProbes) names_.resize(ipc::kMaxProbes);
    channels_.assign(names_.size() + 1, std::vector<double>(capacity_, 0.0));
    head_ = size_ = 0;
    newest_tick_ = received_ = 0;
}

void ProbeHistory::append(const ipc::ProbeFrame& f) {
    const std::size_t probes = names_.size();
    for (std::size_t p = 0; p < probes; ++p) channels_[p][head_] = p < f.count ? f.values[p] : 0.0;
    channels_[probes][head_] = f.output;
    head_ = (head_ + 1) % capacity_;
    size_ = std::min(size_ + 1, capacity_);
    newest_tick_ = f.tick;
    ++received_;
}

int ProbeHistory::channel(const std::string& name) const {
    for (std::size_t i = 0; i < names_.size(); ++i)
        if (names_[i] == name) return static_cast<int>(i);
    return -2;
}

double ProbeHistory::at(int channel, std::size_t age) const {
    const std::size_t c = channel == kOutput ? names_.size() : static_cast<std::size_t>(channel);
    return channels_[c][(head_ + capacity_ - 1 - age) % capacity_];
}

std::vector<double> ProbeHistory::window(int channel, std::size_t count, std::size_t back) const {
    std::vector<double> values;
    if (channel < kOutput || channel >= static_cast<int>(names_.size()) || back >= size_)
        return values;
    count = std::min(count, size_ - back);
    values.reserve(count);
    for (std::size_t i = count; i-- > 0;) values.push_back(at(channel, back + i));
    return values;
}

double ProbeHistory::latest(int channel) const {
    if (size_ == 0 || channel < kOutput || channel >= static_cast<int>(names_.size())) return 0;
    return at(channel, 0);
}

}  // namespace archet::ui
