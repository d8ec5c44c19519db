// `archet new bowed-string`: builds a bowed string (full bandwidth, two-parameter losses, a
// stroke in its Helmholtz band; or the paper's chaplet) and writes it as a model file.

#include <iostream>
#include <memory>

#include "archet/builders/bowed_string.hpp"
#include "archet/common/input_error.hpp"
#include "archet/files/model_file.hpp"
#include "commands.hpp"
#include "option_checks.hpp"

namespace archet::cli {

void add_new_command(CLI::App& app, Action& action) {
    auto* cmd = app.add_subcommand("new", "Build a model from a template and write it to a file");
    cmd->require_subcommand(1);
    auto* bowed = cmd->add_subcommand("bowed-string",
                                      "The paper's bowed string: chaplet, bridges, bow module");
    auto o = std::make_shared<BowedStringOptions>();
    auto output = std::make_shared<std::string>();
    auto no_gesture = std::make_shared<bool>(false);
    bowed->add_option("--pitch", o->pitch, "First mode of the string (Hz)")->capture_default_str();
    auto tuning = std::make_shared<std::string>("homogeneous");
    bowed
        ->add_option(
            "--tuning", *tuning,
            "homogeneous (equal masses, flat partials) or harmonic (first N partials on k·f0)")
        ->check(CLI::IsMember({"homogeneous", "harmonic"}))
        ->capture_default_str();
    auto structure = std::make_shared<std::string>("chain");
    bowed
        ->add_option("--structure", *structure,
                     "chain (masses and links) or modal (its exact modal equivalent: one "
                     "oscillator per mode)")
        ->check(CLI::IsMember({"chain", "modal"}))
        ->capture_default_str();
    bowed->add_flag("--paper", o->paper,
                    "The paper's chaplet: 25-60 masses, link damping alone, no body");
    bowed
        ->add_option("--masses", o->masses,
                     "Masses in the chaplet, up to what the scheme allows at the pitch (0 = full "
                     "bandwidth; with --paper 25-60, 0 = largest stable)")
        ->capture_default_str();
    auto* position = bowed
                         ->add_option("--bow-position", o->bow_position,
                                      "Beta: bow distance from the bridge / string length")
                         ->capture_default_str();
    bowed
        ->add_option("--string-damping", o->string_damping,
                     "Damping of each string link (N·s/m), set by hand; negative = from the decays")
        ->capture_default_str();
    bowed
        ->add_option("--string-t60", o->string_t60,
                     "60 dB decay of the first mode, all losses included (s; 0 = a violin A "
                     "string's at the pitch; --paper: 4 s from link damping)")
        ->capture_default_str();
    bowed
        ->add_option("--string-t60-high", o->string_t60_high,
                     "60 dB decay at --string-t60-high-hz (s; 0 = a violin A string's)")
        ->capture_default_str();
    bowed
        ->add_option("--string-t60-high-hz", o->string_t60_high_hz,
                     "Frequency of --string-t60-high (Hz; 0 = 2000, or twice a pitch above 1 kHz)")
        ->capture_default_str();
    auto* body =
        bowed
            ->add_option(
                "--body", o->body,
                "A body at the bridge, its radiated sound the output: a preset name or none")
            ->capture_default_str();
    bowed->add_flag("--point-bow", o->point_bow,
                    "The bow rubs one mass (the paper's) instead of a hair-wide contact point; "
                    "on a full-bandwidth string it finds almost no Helmholtz band, so pair it "
                    "with --paper or --no-gesture");
    bowed->add_flag("--finger", o->finger,
                    "Add a finger (\"finger\") pressed on the string: move it with "
                    "finger.position, lift it with finger.pressure");
    bowed
        ->add_option("--finger-position", o->finger_position,
                     "Where the finger stops the string: the sounding share of its length, "
                     "from the bridge (1 = open; 2/3 a fifth up, 1/2 an octave)")
        ->capture_default_str();
    bowed->add_option("--stroke-speed", o->stroke_speed, "Bow speed of the embedded stroke (m/s)")
        ->capture_default_str();
    bowed->add_option("--sample-rate", o->sample_rate, "Audio rate level (Hz)")
        ->capture_default_str()
        ->check(sample_rate_range());
    bowed->add_option("--haptic-divider", o->haptic_divider, "Haptic rate = sample rate / divider")
        ->capture_default_str();
    bowed->add_option("--tension", o->tension, "String tension (N)")->capture_default_str();
    bowed->add_option("--density", o->linear_density, "String linear density (kg/m)")
        ->capture_default_str();
    bowed->add_option("--mu-s", o->mu_s, "Static friction coefficient")->capture_default_str();
    bowed->add_option("--mu-d", o->mu_d, "Dynamic friction coefficient (fast sliding)")
        ->capture_default_str();
    bowed->add_option("--v0", o->v0, "Velocity scale of the friction curve (m/s)")
        ->capture_default_str();
    bowed->add_option("--bow-mass", o->bow_mass, "Bow mass on the sliding axis (kg)")
        ->capture_default_str();
    bowed
        ->add_option("--buffer-stiffness", o->buffer_stiffness,
                     "Bow-string contact stiffness (N/m)")
        ->capture_default_str();
    bowed
        ->add_option("--output-gain", o->output_gain,
                     "Output to full scale (0 = the embedded stroke peaks at -6 dBFS; the "
                     "paper's strings 1.5 per N of bridge force)")
        ->capture_default_str();
    bowed->add_flag("--no-gesture", *no_gesture,
                    "Do not embed a stroke (else a steady one in the string's Helmholtz band)");
    bowed->add_option("-o,--output", *output, "Model file to write (.json)")->required();
    bowed->callback([&action, o, output, no_gesture, tuning, structure, body, position] {
        const bool body_given = body->count() > 0;
        o->bow_position_fixed = position->count() > 0;
        action = [o, output, no_gesture, tuning, structure, body_given] {
            if (o->paper && body_given)
                throw InputError("--body", "the paper's strings have no body; leave out --paper");
            o->structure = *structure == "modal" ? Structure::Modal : Structure::Chain;
            o->with_gesture = !*no_gesture;
            o->tuning = *tuning == "harmonic" ? Tuning::Harmonic : Tuning::Homogeneous;
            const Model model = build_bowed_string(*o);
            write_file_atomically(*output, format_model(model));
            std::cout << "wrote " << *output << ": " << model.description << "\n";
            return 0;
        };
    });
}

}  // namespace archet::cli
