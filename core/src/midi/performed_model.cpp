// What the MIDI performer needs of a model, read once when it loads (the open string's first
// mode takes a modal analysis): the engine and the LV2 plugin both play through it.

#include "archet/analysis/playability.hpp"
#include "archet/analysis/string_first_mode.hpp"
#include "archet/common/input_error.hpp"
#include "archet/midi/midi_performer.hpp"

namespace archet::midi {

PerformedModel performed_model(const Model& model) {
    PerformedModel p;
    p.newtons_per_press = force_for_press(model, 1.0);  // throws without a bow module
    if (const Lia* finger = first_finger(model)) {
        p.finger = finger->id;
        // Notes are placed against the open string: its f1 with the finger lifted.
        Model open = model;
        for (auto& l : open.lias)
            if (l.kind == LiaKind::Finger) l.pressure = 0;
        p.open_string_hz = string_first_mode(open).frequency;
        if (!(p.open_string_hz > 0))
            throw InputError(finger->id, "the string along the finger has no first mode");
    }
    return p;
}

}  // namespace archet::midi
