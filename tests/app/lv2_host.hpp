#pragma once
// A small LV2 host written for the tests, on lilv as hosts are: it finds archet.lv2 in the build
// tree, provides urid:map and a worker (run synchronously between two runs, as a host's worker
// thread would between cycles), connects the ports and feeds MIDI events and patch:Set messages
// through the control port as an atom sequence.

#include <lilv/lilv.h>
#include <lv2/atom/atom.h>
#include <lv2/midi/midi.h>
#include <lv2/patch/patch.h>
#include <lv2/state/state.h>
#include <lv2/urid/urid.h>
#include <lv2/worker/worker.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "archet/realtime_thread_mark.hpp"

namespace archet::test {

class Lv2Host {
  public:
    static constexpr const char* kUri = "urn:archet:bowed-string";

    explicit Lv2Host(const std::string& bundle, double rate = 48000) : rate_(rate) {
        world_ = lilv_world_new();
        // The system's specifications (lv2core's plugin classes among them), then the bundle.
        LilvNode* system = lilv_new_string(world_, "/usr/lib/lv2");
        lilv_world_set_option(world_, LILV_OPTION_LV2_PATH, system);
        lilv_node_free(system);
        lilv_world_load_all(world_);
        LilvNode* bundle_uri = lilv_new_file_uri(world_, nullptr, (bundle + "/").c_str());
        lilv_world_load_bundle(world_, bundle_uri);
        lilv_node_free(bundle_uri);
        LilvNode* uri = lilv_new_uri(world_, kUri);
        plugin_ = lilv_plugins_get_by_uri(lilv_world_get_all_plugins(world_), uri);
        lilv_node_free(uri);
        map_ = {this, [](LV2_URID_Map_Handle h, const char* u) {
                    return static_cast<Lv2Host*>(h)->urid(u);
                }};
        // Real-time safe, as a host's must be: copied into slots made beforehand.
        schedule_ = {this, [](LV2_Worker_Schedule_Handle h, std::uint32_t size, const void* data) {
                         auto& host = *static_cast<Lv2Host*>(h);
                         if (host.queued_ == host.requests_.size() || size > kRequestBytes)
                             return LV2_WORKER_ERR_NO_SPACE;
                         std::memcpy(host.requests_[host.queued_].data(), data, size);
                         host.request_sizes_[host.queued_++] = size;
                         return LV2_WORKER_SUCCESS;
                     }};
        map_feature_ = {LV2_URID__map, &map_};
        schedule_feature_ = {LV2_WORKER__schedule, &schedule_};
        if (plugin_) instance_ = lilv_plugin_instantiate(plugin_, rate_, features_);
        if (!instance_) return;
        worker_ = static_cast<const LV2_Worker_Interface*>(
            lilv_instance_get_extension_data(instance_, LV2_WORKER__interface));
        state_ = static_cast<const LV2_State_Interface*>(
            lilv_instance_get_extension_data(instance_, LV2_STATE__interface));
        lilv_instance_connect_port(instance_, 0, control_.data());
        for (std::uint32_t i = 0; i < 4; ++i)
            lilv_instance_connect_port(instance_, 2 + i, &controls_[i]);
        lilv_instance_activate(instance_);
    }
    ~Lv2Host() {
        if (instance_) {
            lilv_instance_deactivate(instance_);
            lilv_instance_free(instance_);
        }
        lilv_world_free(world_);
    }
    Lv2Host(const Lv2Host&) = delete;
    Lv2Host& operator=(const Lv2Host&) = delete;

    const LilvPlugin* plugin() const { return plugin_; }
    LilvWorld* world() const { return world_; }
    bool ready() const { return instance_ != nullptr; }
    /// Bow force (N), bow speed (m/s), bow position (β; 0: the model's), string damping (×).
    float& control(int index) { return controls_[index]; }

    void midi(std::vector<std::uint8_t> bytes) {
        events_.push_back({urid(LV2_MIDI__MidiEvent), bytes});
    }
    /// A patch:Set of the plugin's model to `path`.
    void set_model(const std::string& path) {
        std::vector<std::uint8_t> body(16 + 16 + 16 + path.size() + 1 + 8, 0);
        auto put = [&](std::size_t at, std::uint32_t v) { std::memcpy(&body[at], &v, 4); };
        put(0, 0), put(4, urid(LV2_PATCH__Set));  // object body: id, otype
        put(8, urid(LV2_PATCH__property)), put(12, 0);
        put(16, 4), put(20, urid(LV2_ATOM__URID)), put(24, urid("urn:archet:bowed-string#model"));
        put(32, urid(LV2_PATCH__value)), put(36, 0);
        put(40, static_cast<std::uint32_t>(path.size() + 1)), put(44, urid(LV2_ATOM__Path));
        std::memcpy(&body[48], path.c_str(), path.size() + 1);
        body.resize(48 + path.size() + 1);
        events_.push_back({urid(LV2_ATOM__Object), body});
    }

    /// One run of `frames` samples with the events queued (at its first frame), marked as a
    /// real-time thread's when asked (the allocation count then covers run() alone); then the
    /// worker's requests, answered before the next run.
    std::vector<float> run(std::uint32_t frames, bool as_realtime = false) {
        write_sequence();
        std::vector<float> out(frames);
        lilv_instance_connect_port(instance_, 1, out.data());
        if (as_realtime) {
            const RealtimeThreadMark mark;
            lilv_instance_run(instance_, frames);
        } else {
            lilv_instance_run(instance_, frames);
        }
        serve_worker();
        return out;
    }
    void serve_worker() {
        std::vector<std::vector<char>> responses;
        for (std::size_t i = 0; i < queued_; ++i)
            worker_->work(
                lilv_instance_get_handle(instance_),
                [](LV2_Worker_Respond_Handle h, std::uint32_t size, const void* data) {
                    auto* bytes = static_cast<const char*>(data);
                    static_cast<std::vector<std::vector<char>>*>(h)->emplace_back(bytes,
                                                                                  bytes + size);
                    return LV2_WORKER_SUCCESS;
                },
                &responses, request_sizes_[i], requests_[i].data());
        queued_ = 0;
        for (const auto& r : responses)
            worker_->work_response(lilv_instance_get_handle(instance_),
                                   static_cast<std::uint32_t>(r.size()), r.data());
    }
    /// The model path the plugin's state holds, saved with the host `features` given.
    std::string saved_model(const LV2_Feature* const* features = nullptr) {
        std::string saved;
        state_->save(
            lilv_instance_get_handle(instance_),
            [](LV2_State_Handle h, std::uint32_t, const void* value, std::size_t size,
               std::uint32_t, std::uint32_t) {
                static_cast<std::string*>(h)->assign(static_cast<const char*>(value), size - 1);
                return LV2_STATE_SUCCESS;
            },
            &saved, 0, features);
        return saved;
    }
    /// Restores a state whose model path is `stored`, with the host `features` given.
    bool restore_model(const std::string& stored, const LV2_Feature* const* features = nullptr) {
        struct Stored {
            const std::string* path;
            LV2_URID type;
        } value{&stored, urid(LV2_ATOM__Path)};
        return state_->restore(
                   lilv_instance_get_handle(instance_),
                   [](LV2_State_Handle h, std::uint32_t, std::size_t* size, std::uint32_t* type,
                      std::uint32_t* flags) -> const void* {
                       const auto& v = *static_cast<const Stored*>(h);
                       *size = v.path->size() + 1, *type = v.type;
                       *flags = LV2_STATE_IS_POD | LV2_STATE_IS_PORTABLE;
                       return v.path->c_str();
                   },
                   &value, 0, features) == LV2_STATE_SUCCESS;
    }
    LV2_URID urid(const std::string& uri) {
        auto [it, added] = urids_.emplace(uri, static_cast<LV2_URID>(urids_.size() + 1));
        return it->second;
    }

  private:
    struct Event {
        LV2_URID type;
        std::vector<std::uint8_t> body;
    };
    void write_sequence() {
        std::fill(control_.begin(), control_.end(), 0);
        auto* seq = reinterpret_cast<LV2_Atom_Sequence*>(control_.data());
        seq->atom.type = urid(LV2_ATOM__Sequence);
        seq->atom.size = sizeof(LV2_Atom_Sequence_Body);
        auto* at = reinterpret_cast<std::uint8_t*>(seq + 1);
        for (const Event& e : events_) {
            auto* ev = reinterpret_cast<LV2_Atom_Event*>(at);
            ev->time.frames = 0;
            ev->body.type = e.type;
            ev->body.size = static_cast<std::uint32_t>(e.body.size());
            std::memcpy(ev + 1, e.body.data(), e.body.size());
            const std::uint32_t step = (sizeof(LV2_Atom_Event) + ev->body.size + 7) & ~7u;
            at += step;
            seq->atom.size += step;
        }
        events_.clear();
    }

    double rate_;
    LilvWorld* world_ = nullptr;
    const LilvPlugin* plugin_ = nullptr;
    LilvInstance* instance_ = nullptr;
    const LV2_Worker_Interface* worker_ = nullptr;
    const LV2_State_Interface* state_ = nullptr;
    std::map<std::string, LV2_URID> urids_;
    LV2_URID_Map map_;
    LV2_Worker_Schedule schedule_;
    LV2_Feature map_feature_, schedule_feature_;
    const LV2_Feature* features_[3] = {&map_feature_, &schedule_feature_, nullptr};
    static constexpr std::size_t kRequestBytes = 4096;
    std::array<std::array<char, kRequestBytes>, 16> requests_{};
    std::array<std::uint32_t, 16> request_sizes_{};
    std::size_t queued_ = 0;
    std::vector<Event> events_;
    alignas(8) std::array<std::uint8_t, 1 << 16> control_{};
    float controls_[4] = {0.15f, 0.1f, 0.0f, 1.0f};
};

}  // namespace archet::test
