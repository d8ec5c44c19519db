// The table of element parameters: every kind's parameters round-trip through set/get and
// through a model file, out-of-range values are refused naming the element and parameter,
// and ELEMENT.PARAMETER parses in one place.

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "archet/common/input_error.hpp"
#include "archet/files/model_file.hpp"
#include "archet/model/element_kinds.hpp"
#include "archet/model/model_parameters.hpp"
#include "archet/physics/compiled_model.hpp"

namespace archet {
namespace {

const MatKind kMatKinds[] = {MatKind::Mass, MatKind::Fixed, MatKind::Oscillator, MatKind::Gesture,
                             MatKind::ModalPoint};
const LiaKind kLiaKinds[] = {LiaKind::Spring, LiaKind::Damper,      LiaKind::SpringDamper,
                             LiaKind::Buffer, LiaKind::BowFriction, LiaKind::Finger};

// One element of every kind (no validation: the table does not need a playable model).
Model every_kind() {
    Model m;
    for (MatKind k : kMatKinds) {
        Mat mat;
        mat.id = std::string("m_") + to_string(k), mat.kind = k, mat.mass = 1;
        if (k == MatKind::ModalPoint) mat.modes = {"m_mass"}, mat.weights = {1.0};
        m.mats.push_back(mat);
    }
    for (LiaKind k : kLiaKinds) {
        Lia lia;
        lia.id = std::string("l_") + to_string(k), lia.kind = k;
        lia.from = "m_mass", lia.to = "m_fixed", lia.press = "m_mass", lia.surface = "m_fixed";
        if (k == LiaKind::Finger) lia.from = lia.to = "", lia.along = {"m_mass", "m_fixed"};
        m.lias.push_back(lia);
    }
    return m;
}

// A value inside the range, different for every row, so a swapped field shows.
double value_inside(const ParameterInfo& p, int row) {
    const double v = 0.125 * (row + 1);
    return std::clamp(v, p.minimum + (p.strictly_positive ? 1e-3 : 0.0), p.maximum);
}

std::vector<std::pair<ParameterName, ParameterInfo>> all_parameters(const Model& m) {
    std::vector<std::pair<ParameterName, ParameterInfo>> out;
    for (const auto& e : m.mats)
        for (const auto& p : element_parameters(m, e.id)) out.push_back({{e.id, p.name}, p});
    for (const auto& e : m.lias)
        for (const auto& p : element_parameters(m, e.id)) out.push_back({{e.id, p.name}, p});
    return out;
}

TEST(ElementKinds, EveryParameterRoundTripsThroughSetGetAndTheFile) {
    Model m = every_kind();
    const auto parameters = all_parameters(m);
    ASSERT_EQ(parameters.size(), 30u);  // 12 on masses, 18 on links
    int row = 0;
    for (const auto& [name, info] : parameters) {
        set_parameter(m, name, value_inside(info, row));
        EXPECT_EQ(get_parameter(m, name), value_inside(info, row)) << name.text();
        ++row;
    }
    const Model read = parse_model(format_model(m), "round trip");
    row = 0;
    for (const auto& [name, info] : parameters)
        EXPECT_EQ(get_parameter(read, name), value_inside(info, row++)) << name.text();
    EXPECT_EQ(format_model(read), format_model(m));
}

TEST(ElementKinds, RangesRefuseValuesNamingTheElementAndParameter) {
    Model m = every_kind();
    for (const auto& [name, info] : all_parameters(m)) {
        const double before = get_parameter(m, name);
        const double below = info.strictly_positive ? info.minimum : info.minimum - 1;
        for (double bad : {below, 2 * info.maximum, std::nan("")}) {
            try {
                set_parameter(m, name, bad);
                ADD_FAILURE() << name.text() << " took " << bad;
            } catch (const InputError& e) {
                EXPECT_EQ(e.where(), name.text());
                EXPECT_NE(e.message().find("must be"), std::string::npos) << e.what();
            }
            EXPECT_EQ(get_parameter(m, name), before) << "a refused value changes nothing";
        }
    }
}

TEST(ElementKinds, UnknownNamesListTheKindsParameters) {
    const Model m = every_kind();
    try {
        get_parameter(m, {"l_bow_friction", "stiffness"});
        FAIL() << "a bow's stiffness is its buffer_stiffness";
    } catch (const InputError& e) {
        EXPECT_EQ(e.where(), "l_bow_friction");
        EXPECT_NE(e.message().find("buffer_stiffness, buffer_damping, mu_s, mu_d, v0"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_THROW(get_parameter(m, {"nothing", "mass"}), InputError);
}

TEST(ElementKinds, SharedFieldsHaveTheirKindsNames) {
    Model m = every_kind();
    set_parameter(m, {"l_buffer", "gap"}, 0.002);
    set_parameter(m, {"l_bow_friction", "buffer_stiffness"}, 3e4);
    set_parameter(m, {"l_bow_friction", "buffer_damping"}, 2.0);
    EXPECT_EQ(m.find_lia("l_buffer")->gap(), 0.002);
    EXPECT_EQ(m.find_lia("l_bow_friction")->buffer_stiffness(), 3e4);
    EXPECT_EQ(m.find_lia("l_bow_friction")->buffer_damping(), 2.0);
    EXPECT_THROW(get_parameter(m, {"l_buffer", "length"}), InputError);
}

TEST(ElementKinds, RowsAreConsistent) {
    auto check = [](const auto& rows, const std::string& kind) {
        std::set<std::string> names;
        for (const auto& r : rows) {
            EXPECT_TRUE(names.insert(r.info.name).second) << kind << " repeats " << r.info.name;
            EXPECT_LT(r.info.minimum, r.info.maximum) << kind << "." << r.info.name;
            const bool linear = r.role == ParameterRole::Mass ||
                                r.role == ParameterRole::Stiffness ||
                                r.role == ParameterRole::Damping;
            // A finger is solved implicitly: its stiffness and damping bound no step.
            EXPECT_EQ(r.info.stability_relevant, linear && kind != "finger")
                << kind << "." << r.info.name;
            if (r.file_default) {
                EXPECT_TRUE(r.info.minimum <= *r.file_default);
            }
        }
    };
    for (MatKind k : kMatKinds) check(kind_parameters(k), to_string(k));
    for (LiaKind k : kLiaKinds) check(kind_parameters(k), to_string(k));
}

TEST(ElementKinds, AFileMayLeaveOutOnlyParametersWithADefault) {
    const std::string head = R"({"format": "archet-model", "version": 1, "masses": [)";
    const Model m = parse_model(head + R"({"id": "a", "type": "mass", "mass": 0.5}], "links": []})",
                                "defaults");
    EXPECT_EQ(m.mats[0].velocity, 0.0);
    EXPECT_EQ(m.mats[0].position, 0.0);
    try {
        parse_model(head + R"({"id": "a", "type": "mass"}], "links": []})", "no mass");
        FAIL() << "a mass needs its mass";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("mass"), std::string::npos) << e.what();
    }
}

TEST(ElementKinds, TheCompiledModelResolvesByTheTablesNames) {
    Model m;
    // Member by member: designated initializers would leave the other members to warn about.
    Mat wall, osc;
    wall.id = "wall", wall.kind = MatKind::Fixed;
    osc.id = "osc", osc.kind = MatKind::Oscillator, osc.mass = 1, osc.stiffness = 10;
    m.mats = {wall, osc};
    Lia buffer;
    buffer.id = "buf", buffer.kind = LiaKind::Buffer, buffer.from = "osc", buffer.to = "wall";
    buffer.stiffness = 100, buffer.length = 0.01;
    m.lias.push_back(buffer);
    const CompiledModel c = compile(m);
    EXPECT_EQ(c.resolve_parameter({"buf", "gap"}).kind, ParameterSlot::Kind::LinkLength);
    EXPECT_EQ(c.resolve_parameter({"osc", "stiffness"}).kind, ParameterSlot::Kind::GroundK);
    EXPECT_NO_THROW(c.resolve_parameter({"osc", "damping"}));
    EXPECT_NO_THROW(c.resolve_parameter({"wall", "position"}));
    EXPECT_THROW(c.resolve_parameter({"buf", "length"}), InputError) << "a buffer has a gap";
    EXPECT_THROW(c.resolve_parameter({"osc", "velocity"}), InputError) << "initial condition";
}

TEST(ParameterName, ParsesAtTheLastDot) {
    const auto name = ParameterName::parse("bow.mu_s");
    EXPECT_EQ(name.element, "bow");
    EXPECT_EQ(name.parameter, "mu_s");
    EXPECT_EQ(name.text(), "bow.mu_s");
    EXPECT_EQ(ParameterName::parse("left.bow.v0"), (ParameterName{"left.bow", "v0"}));
}

TEST(ParameterName, SaysWhatIsMissing) {
    const std::pair<const char*, const char*> bad[] = {{"", "is empty"},
                                                       {"mu_s", "has no '.'"},
                                                       {".mu_s", "no element before"},
                                                       {"bow.", "no parameter after"}};
    for (const auto& [text, reason] : bad) {
        try {
            ParameterName::parse(text, "--set");
            ADD_FAILURE() << '"' << text << "\" parsed";
        } catch (const InputError& e) {
            EXPECT_EQ(e.where(), "--set");
            EXPECT_NE(e.message().find(reason), std::string::npos) << e.what();
            EXPECT_NE(e.message().find("ELEMENT.PARAMETER"), std::string::npos) << e.what();
        }
    }
    try {
        ParameterName::parse("mu_s");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(e.where(), "\"mu_s\"") << "without a place, the text itself is named";
    }
}

TEST(ParameterName, AssignmentsGoThroughIt) {
    Model m = every_kind();
    apply_assignment(m, "l_bow_friction.mu_s=0.7");
    EXPECT_EQ(m.find_lia("l_bow_friction")->mu_static, 0.7);
    EXPECT_THROW(apply_assignment(m, ".mu_s=0.7"), InputError);
    EXPECT_THROW(apply_assignment(m, "l_bow_friction.mu_s"), InputError);
    EXPECT_THROW(apply_assignment(m, "l_bow_friction.mu_s=x"), InputError);
}

}  // namespace
}  // namespace archet
