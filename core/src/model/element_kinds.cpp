#include "archet/model/element_kinds.hpp"

#include "archet/common/input_limits.hpp"

namespace archet {

namespace {

using namespace limits;
using R = ParameterRole;
constexpr bool kStable = true;  // the stability bound depends on it
constexpr bool kFree = false;
constexpr bool kAboveZero = true;  // strictly positive
constexpr bool kZeroOrMore = false;

// The rows kinds share, so that a unit or range is written once.
MatParameter mat_position() {
    return {
        {"position", "m", -kPosition, false, kPosition, kFree}, R::Position, &Mat::position, 0.0};
}
MatParameter mat_mass() {
    return {{"mass", "kg", 0.0, true, kMass, kStable}, R::Mass, &Mat::mass, std::nullopt};
}
MatParameter mat_velocity() {
    return {
        {"velocity", "m/s", -kVelocity, false, kVelocity, kFree}, R::Velocity, &Mat::velocity, 0.0};
}
LiaParameter lia_stiffness(const char* name, bool positive) {
    return {{name, "N/m", 0.0, positive, kStiffness, kStable},
            R::Stiffness,
            &Lia::stiffness,
            std::nullopt};
}
LiaParameter lia_damping(const char* name, bool positive, std::optional<double> file_default) {
    return {
        {name, "N·s/m", 0.0, positive, kDamping, kStable}, R::Damping, &Lia::damping, file_default};
}
LiaParameter lia_length(const char* name) {
    return {{name, "m", -kPosition, false, kPosition, kFree}, R::Length, &Lia::length, 0.0};
}

}  // namespace

const std::vector<MatParameter>& kind_parameters(MatKind kind) {
    static const std::vector<MatParameter> mass{mat_position(), mat_mass(), mat_velocity()};
    static const std::vector<MatParameter> oscillator{
        mat_position(),
        mat_mass(),
        mat_velocity(),
        {{"stiffness", "N/m", 0.0, false, kStiffness, kStable},
         R::Stiffness,
         &Mat::stiffness,
         std::nullopt},
        {{"damping", "N·s/m", 0.0, false, kDamping, kStable}, R::Damping, &Mat::damping, 0.0}};
    static const std::vector<MatParameter> fixed{mat_position()};
    static const std::vector<MatParameter> gesture{
        mat_position(),
        {{"position_scale", "m/m", -kScale, false, kScale, kFree},
         R::PositionScale,
         &Mat::position_scale,
         1.0},
        {{"force_scale", "N/N", -kScale, false, kScale, kFree},
         R::ForceScale,
         &Mat::force_scale,
         1.0}};
    static const std::vector<MatParameter> none;
    switch (kind) {
        case MatKind::Mass:
            return mass;
        case MatKind::Oscillator:
            return oscillator;
        case MatKind::Fixed:
            return fixed;
        case MatKind::Gesture:
            return gesture;
        case MatKind::ModalPoint:
            break;
    }
    return none;
}

const std::vector<LiaParameter>& kind_parameters(LiaKind kind) {
    // A spring without stiffness, or a damper without damping, joins nothing.
    static const std::vector<LiaParameter> spring{lia_stiffness("stiffness", kAboveZero),
                                                  lia_length("length")};
    static const std::vector<LiaParameter> damper{lia_damping("damping", kAboveZero, std::nullopt)};
    static const std::vector<LiaParameter> spring_damper{lia_stiffness("stiffness", kZeroOrMore),
                                                         lia_damping("damping", kZeroOrMore, 0.0),
                                                         lia_length("length")};
    // A buffer's `length` is the gap it closes before it touches.
    static const std::vector<LiaParameter> buffer{lia_stiffness("stiffness", kAboveZero),
                                                  lia_damping("damping", kZeroOrMore, 0.0),
                                                  lia_length("gap")};
    // The bow's `stiffness`/`damping` are those of its elastic buffer on the pressure axis.
    static const std::vector<LiaParameter> bow{
        lia_stiffness("buffer_stiffness", kAboveZero),
        lia_damping("buffer_damping", kZeroOrMore, 0.0),
        {{"mu_s", "", 0.0, true, 10.0, kFree}, R::MuStatic, &Lia::mu_static, std::nullopt},
        {{"mu_d", "", 0.0, false, 10.0, kFree}, R::MuDynamic, &Lia::mu_dynamic, std::nullopt},
        {{"v0", "m/s", 0.0, true, 100.0, kFree}, R::V0, &Lia::v0, std::nullopt}};
    // A finger: its full stiffness and damping (pressure 1), where it touches and how hard.
    // None bounds the step: the finger is solved implicitly (simulation_finger.cpp).
    static const std::vector<LiaParameter> finger{
        {{"stiffness", "N/m", 0.0, true, kStiffness, kFree},
         R::Stiffness,
         &Lia::stiffness,
         std::nullopt},
        {{"damping", "N·s/m", 0.0, false, kDamping, kFree}, R::Damping, &Lia::damping, 0.0},
        {{"position", "", 0.0, false, 1.0, kFree},
         R::FingerPosition,
         &Lia::finger_position,
         std::nullopt},
        {{"pressure", "", 0.0, false, 1.0, kFree}, R::Pressure, &Lia::pressure, 1.0}};
    switch (kind) {
        case LiaKind::Finger:
            return finger;
        case LiaKind::Spring:
            return spring;
        case LiaKind::Damper:
            return damper;
        case LiaKind::SpringDamper:
            return spring_damper;
        case LiaKind::Buffer:
            return buffer;
        case LiaKind::BowFriction:
            break;
    }
    return bow;
}

}  // namespace archet
