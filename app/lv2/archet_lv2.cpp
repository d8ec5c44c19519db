// archet.lv2: an Archet model as an LV2 instrument. MIDI in (notes, controllers, the pitch
// wheel, through the same performer as the engine), audio out, and control ports for the bow's
// force, speed and position and the string's damping. The model is a plugin parameter
// (patch:Set of archet#model, a file path) kept in the plugin's state; it is read and compiled
// in the worker, as is a new bow position, and swapped in at the start of a run. run() itself
// only plays: no allocation, no lock, no I/O.

#include <lv2/atom/atom.h>
#include <lv2/atom/util.h>
#include <lv2/core/lv2.h>
#include <lv2/midi/midi.h>
#include <lv2/patch/patch.h>
#include <lv2/state/state.h>
#include <lv2/urid/urid.h>
#include <lv2/worker/worker.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <utility>

#include "archet/files/model_file.hpp"
#include "lv2_instrument.hpp"

namespace archet::lv2 {

namespace {

constexpr const char* kUri = "urn:archet:bowed-string";
constexpr const char* kModelUri = "urn:archet:bowed-string#model";

enum Port : std::uint32_t { Control, Out, BowForce, BowSpeed, BowPosition, StringDamping };

struct Uris {
    LV2_URID midi_event, atom_path, atom_urid, atom_object, atom_blank, patch_set, patch_property,
        patch_value, model;
};

// What the worker is asked: load a model file, rebuild the instrument with the bow elsewhere,
// or delete an instrument run() let go of. Sent as long as its path (hosts' request rings are
// a few kilobytes).
struct Work {
    enum Kind : std::uint32_t { Load, Rebuild, Free } kind;
    double bow_position = 0;
    Instrument* garbage = nullptr;
    char path[2048] = {};
    std::uint32_t size() const {
        return static_cast<std::uint32_t>(offsetof(Work, path) +
                                          (kind == Load ? strnlen(path, sizeof path) + 1 : 0));
    }
};

struct Plugin {
    double rate = 48000;
    LV2_URID_Map* map = nullptr;
    LV2_Worker_Schedule* schedule = nullptr;
    Uris uris{};
    const LV2_Atom_Sequence* control = nullptr;
    float* out = nullptr;
    const float* ports[6] = {};
    Instrument* playing = nullptr;         ///< run()'s
    Instrument* arrived = nullptr;         ///< from the worker, taken at the next run()
    bool rebuilding = false;               ///< a bow-position rebuild is with the worker
    std::array<Instrument*, 8> garbage{};  ///< let go of, not yet taken by the worker
    double bow_port = -1;                  ///< the bow position port as last seen
    double bow_target = 0;  ///< β asked for last, by the port or by MIDI (0: the model's)
    double bow_built = 0;   ///< β last given to the worker (not asked again if it fails)
    // The worker's (and instantiate's, restore's):
    Model base;
    std::optional<ChainBuild> base_build;  ///< timed when the base was loaded, kept by rebuilds
    std::uint64_t model_id = 1;
    std::mutex path_mutex;  ///< the worker and state save
    std::string model_path;
};

// Off the audio thread: a model file checked and compiled, or nothing (said on stderr).
Instrument* build(Plugin& p, const Model& model, double bow_position,
                  std::optional<ChainBuild> chain_build = std::nullopt) {
    try {
        auto instrument = std::make_unique<Instrument>(model, p.rate, bow_position, chain_build);
        instrument->set_model_id(p.model_id);
        return instrument.release();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "archet.lv2: %s\n", e.what());
        return nullptr;
    }
}

Instrument* load(Plugin& p, const std::string& path, double bow_position) {
    try {
        Model model = load_model_file(path);
        model.sample_rate = p.rate;
        ++p.model_id;  // a new model: nothing of the old one's motion is taken over
        Instrument* fresh = build(p, model, bow_position);
        if (!fresh) {
            --p.model_id;  // the base stays: its rebuilds still take over its motion
            return nullptr;
        }
        p.base = std::move(model);
        p.base_build = fresh->chain_build();
        const std::lock_guard lock(p.path_mutex);
        p.model_path = path;
        return fresh;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "archet.lv2: %s\n", e.what());
        return nullptr;
    }
}

double port(const Plugin& p, Port which, double fallback) {
    return p.ports[which] ? static_cast<double>(*p.ports[which]) : fallback;
}

bool schedule(Plugin& p, const Work& w) {
    return p.schedule->schedule_work(p.schedule->handle, w.size(), &w) == LV2_WORKER_SUCCESS;
}

// Hands an instrument to the worker to delete; kept (and offered again next run) when the
// worker's queue is full, so that nothing leaks.
void let_go(Plugin& p, Instrument* old) {
    for (Instrument*& g : p.garbage) {
        if (!g) continue;
        Work w{Work::Free};
        w.garbage = g;
        if (schedule(p, w)) g = nullptr;
    }
    if (!old) return;
    Work w{Work::Free};
    w.garbage = old;
    if (schedule(p, w)) return;
    for (Instrument*& g : p.garbage)
        if (!g) {
            g = old;
            return;
        }
    std::fprintf(stderr, "archet.lv2: the host's worker is full; an instrument is leaked\n");
}

// A patch:Set of the model to a path: the worker loads it.
void take_patch(Plugin& p, const LV2_Atom_Object* object) {
    const LV2_Atom* property = nullptr;
    const LV2_Atom* value = nullptr;
    lv2_atom_object_get(object, p.uris.patch_property, &property, p.uris.patch_value, &value, 0);
    if (!property || property->type != p.uris.atom_urid ||
        reinterpret_cast<const LV2_Atom_URID*>(property)->body != p.uris.model || !value ||
        value->type != p.uris.atom_path || value->size == 0 || value->size >= sizeof Work::path)
        return;
    Work w{Work::Load};
    w.bow_position = p.bow_target;  // where the port or CC 4 put the bow last
    std::memcpy(w.path, LV2_ATOM_BODY_CONST(value), value->size);
    w.path[value->size] = '\0';
    schedule(p, w);
}

void take_event(Plugin& p, const LV2_Atom_Event* ev) {
    if (ev->body.type == p.uris.midi_event) {
        const auto* bytes = static_cast<const std::uint8_t*>(LV2_ATOM_BODY_CONST(&ev->body));
        if (const auto m = midi::decode_midi(std::span(bytes, ev->body.size)))
            p.playing->receive(*m);
    } else if (ev->body.type == p.uris.atom_object || ev->body.type == p.uris.atom_blank) {
        const auto* object = reinterpret_cast<const LV2_Atom_Object*>(&ev->body);
        if (object->body.otype == p.uris.patch_set) take_patch(p, object);
    }
}

// At the start of a run: the instrument the worker built, carrying on the motion of the one
// it replaces when only the bow moved; the old one goes back to the worker to be deleted.
void swap_in(Plugin& p) {
    Instrument* fresh = std::exchange(p.arrived, nullptr);
    if (!fresh) return let_go(p, nullptr);  // garbage the worker could not take before
    fresh->continue_from(*p.playing);
    let_go(p, std::exchange(p.playing, fresh));
}

LV2_Handle instantiate(const LV2_Descriptor*, double rate, const char* bundle,
                       const LV2_Feature* const* features) {
    auto p = std::make_unique<Plugin>();
    p->rate = rate;
    for (int i = 0; features[i]; ++i) {
        if (!std::strcmp(features[i]->URI, LV2_URID__map))
            p->map = static_cast<LV2_URID_Map*>(features[i]->data);
        if (!std::strcmp(features[i]->URI, LV2_WORKER__schedule))
            p->schedule = static_cast<LV2_Worker_Schedule*>(features[i]->data);
    }
    if (!p->map || !p->schedule) {
        std::fprintf(stderr, "archet.lv2: the host must provide urid:map and worker:schedule\n");
        return nullptr;
    }
    auto map = [&](const char* uri) { return p->map->map(p->map->handle, uri); };
    p->uris = {map(LV2_MIDI__MidiEvent), map(LV2_ATOM__Path),   map(LV2_ATOM__URID),
               map(LV2_ATOM__Object),    map(LV2_ATOM__Blank),  map(LV2_PATCH__Set),
               map(LV2_PATCH__property), map(LV2_PATCH__value), map(kModelUri)};
    // The bundle's own model until the host sets another: a fingered 220 Hz string.
    p->playing = load(*p, std::string(bundle) + "/default.json", 0);
    if (!p->playing) return nullptr;
    return p.release();
}

void connect_port(LV2_Handle handle, std::uint32_t index, void* data) {
    auto& p = *static_cast<Plugin*>(handle);
    if (index == Control)
        p.control = static_cast<const LV2_Atom_Sequence*>(data);
    else if (index == Out)
        p.out = static_cast<float*>(data);
    else if (index <= StringDamping)
        p.ports[index] = static_cast<const float*>(data);
}

void run(LV2_Handle handle, std::uint32_t frames) {
    auto& p = *static_cast<Plugin*>(handle);
    swap_in(p);
    Instrument& playing = *p.playing;
    playing.set_controls(port(p, BowForce, 0.15), port(p, BowSpeed, 0.1),
                         port(p, StringDamping, 1.0));
    // Sample-accurate: render up to each event, then take it.
    std::uint32_t done = 0;
    if (p.control) {
        LV2_ATOM_SEQUENCE_FOREACH(p.control, ev) {
            const auto at =
                std::min<std::uint32_t>(static_cast<std::uint32_t>(ev->time.frames), frames);
            if (at > done) p.playing->render(p.out + done, at - done), done = at;
            take_event(p, ev);
        }
    }
    if (done < frames) p.playing->render(p.out + done, frames - done);
    // The bow where it was asked last, by its port or by MIDI (CC 4): built by the worker.
    const double port_position = port(p, BowPosition, 0);
    if (port_position != p.bow_port) p.bow_port = p.bow_target = port_position;
    if (const double asked = p.playing->take_bow_request(); asked > 0) p.bow_target = asked;
    // A blown-up instrument is silent: the worker builds it afresh (nothing of its state).
    const bool wanted =
        p.playing->blown_up() ||
        (p.bow_target != p.bow_built && std::abs(p.bow_target - p.playing->bow_position()) > 1e-6);
    if (!p.rebuilding && wanted) {
        Work w{Work::Rebuild};
        w.bow_position = p.bow_target;
        if (schedule(p, w)) p.rebuilding = true, p.bow_built = p.bow_target;  // else: next run
    }
}

void cleanup(LV2_Handle handle) {
    auto* p = static_cast<Plugin*>(handle);
    delete p->playing;
    delete p->arrived;
    for (Instrument* g : p->garbage) delete g;
    delete p;
}

// ---- worker ----

LV2_Worker_Status work(LV2_Handle handle, LV2_Worker_Respond_Function respond,
                       LV2_Worker_Respond_Handle respond_handle, std::uint32_t size,
                       const void* data) {
    auto& p = *static_cast<Plugin*>(handle);
    if (size < offsetof(Work, path) || size > sizeof(Work)) return LV2_WORKER_ERR_UNKNOWN;
    Work w;
    std::memcpy(&w, data, size);
    Instrument* fresh = nullptr;
    switch (w.kind) {
        case Work::Free:
            delete w.garbage;
            return LV2_WORKER_SUCCESS;
        case Work::Load:
            w.path[sizeof w.path - 1] = '\0';
            fresh = load(p, w.path, w.bow_position);
            break;
        case Work::Rebuild:
            fresh = build(p, p.base, w.bow_position, p.base_build);
            break;
    }
    // Answered even when nothing was built, so that run() may ask again.
    return respond(respond_handle, sizeof fresh, &fresh);
}

LV2_Worker_Status work_response(LV2_Handle handle, std::uint32_t size, const void* data) {
    auto& p = *static_cast<Plugin*>(handle);
    Instrument* fresh = nullptr;
    if (size == sizeof fresh) std::memcpy(&fresh, data, sizeof fresh);
    p.rebuilding = false;
    if (!fresh) return LV2_WORKER_SUCCESS;
    if (p.arrived) {  // two arrived before a run: the newer wins, the older is let go
        let_go(p, std::exchange(p.arrived, fresh));
    } else {
        p.arrived = fresh;
    }
    return LV2_WORKER_SUCCESS;
}

// ---- state: the model's path ----

// The host's path features for a save or restore: state:mapPath, and state:freePath, which
// frees the paths mapPath returns (they may come from another allocator than ours).
struct HostPaths {
    const LV2_State_Map_Path* map = nullptr;
    const LV2_State_Free_Path* free_path = nullptr;

    explicit HostPaths(const LV2_Feature* const* features) {
        for (int i = 0; features && features[i]; ++i) {
            if (!std::strcmp(features[i]->URI, LV2_STATE__mapPath))
                map = static_cast<const LV2_State_Map_Path*>(features[i]->data);
            if (!std::strcmp(features[i]->URI, LV2_STATE__freePath))
                free_path = static_cast<const LV2_State_Free_Path*>(features[i]->data);
        }
    }
    /// A path the host mapped, copied and freed the host's way; `otherwise` if it gave none.
    std::string take(char* mapped, const std::string& otherwise) const {
        if (!mapped) return otherwise;
        std::string copy = mapped;
        if (free_path)
            free_path->free_path(free_path->handle, mapped);
        else
            std::free(mapped);  // hosts without freePath allocate with malloc (state.h)
        return copy;
    }
};

LV2_State_Status save(LV2_Handle handle, LV2_State_Store_Function store,
                      LV2_State_Handle state_handle, std::uint32_t,
                      const LV2_Feature* const* features) {
    auto& p = *static_cast<Plugin*>(handle);
    std::string path;
    {
        const std::lock_guard lock(p.path_mutex);
        path = p.model_path;
    }
    const HostPaths host(features);
    const std::string stored =
        host.map ? host.take(host.map->abstract_path(host.map->handle, path.c_str()), path) : path;
    return store(state_handle, p.uris.model, stored.c_str(), stored.size() + 1, p.uris.atom_path,
                 LV2_STATE_IS_POD | LV2_STATE_IS_PORTABLE);
}

LV2_State_Status restore(LV2_Handle handle, LV2_State_Retrieve_Function retrieve,
                         LV2_State_Handle state_handle, std::uint32_t,
                         const LV2_Feature* const* features) {
    auto& p = *static_cast<Plugin*>(handle);
    std::size_t size = 0;
    std::uint32_t type = 0, flags = 0;
    const void* value = retrieve(state_handle, p.uris.model, &size, &type, &flags);
    if (!value || type != p.uris.atom_path) return LV2_STATE_ERR_NO_PROPERTY;
    const HostPaths host(features);
    const std::string stored(static_cast<const char*>(value),
                             strnlen(static_cast<const char*>(value), size));
    const std::string path =
        host.map ? host.take(host.map->absolute_path(host.map->handle, stored.c_str()), stored)
                 : stored;
    // Never at the same time as run() (the state extension says so): swapped here.
    Instrument* fresh = load(p, path, port(p, BowPosition, 0));
    if (!fresh) return LV2_STATE_ERR_UNKNOWN;
    delete std::exchange(p.playing, fresh);
    delete std::exchange(p.arrived, nullptr);  // built before the restore: not what is wanted
    return LV2_STATE_SUCCESS;
}

const void* extension_data(const char* uri) {
    static const LV2_Worker_Interface worker{work, work_response, nullptr};
    static const LV2_State_Interface state{save, restore};
    if (!std::strcmp(uri, LV2_WORKER__interface)) return &worker;
    if (!std::strcmp(uri, LV2_STATE__interface)) return &state;
    return nullptr;
}

const LV2_Descriptor kDescriptor{kUri, instantiate, connect_port, nullptr,
                                 run,  nullptr,     cleanup,      extension_data};

}  // namespace

}  // namespace archet::lv2

LV2_SYMBOL_EXPORT const LV2_Descriptor* lv2_descriptor(std::uint32_t index) {
    return index == 0 ? &archet::lv2::kDescriptor : nullptr;
}
