// The inspector reads the parameter table: each field says its unit and range, shows a
// stability margin only for what the bound depends on, and an edit is checked once by the
// document, which undoes to the value it replaced.

#include <gtest/gtest.h>

#include <QLabel>
#include <QLineEdit>
#include <QLocale>

#include <cmath>
#include <vector>

#include "archet/analysis/playability.hpp"
#include "archet/builders/bowed_string.hpp"
#include "archet/files/model_file.hpp"
#include "archet/model/model_parameters.hpp"
#include "archet/model/model_variants.hpp"
#include "archet/model/string_points.hpp"
#include "archet/ui/inspector.hpp"
#include "archet/ui/model_document.hpp"
#include "test_support.hpp"

namespace archet::ui {
namespace {

Model oscillator_on_a_spring() {
    Model m;
    m.name = "inspected";
    m.mats = {test::fixed("wall"), test::mass("a", 0.01)};
    m.lias = {test::spring_damper("k", "wall", "a", 100, 0.01)};
    return m;
}

TEST(Inspector, FieldsShowTheTablesUnitsAndRanges) {
    ModelDocument document;
    document.reset(oscillator_on_a_spring());
    Inspector inspector(document);
    inspector.show_element("a");
    const auto* mass = inspector.findChild<QLineEdit*>("mass");
    ASSERT_NE(mass, nullptr);
    const QString tip = mass->toolTip();
    EXPECT_TRUE(tip.contains("above 0 to 1e+06 kg")) << tip.toStdString();
    EXPECT_TRUE(tip.contains("stability")) << tip.toStdString();
    const auto* velocity = inspector.findChild<QLineEdit*>("velocity");
    ASSERT_NE(velocity, nullptr);
    EXPECT_TRUE(velocity->toolTip().contains("from -100 to 100 m/s"))
        << velocity->toolTip().toStdString();
    EXPECT_FALSE(velocity->toolTip().contains("stability"));
}

TEST(Inspector, AnEditIsCheckedByTheDocumentAndUndoes) {
    ModelDocument document;
    document.reset(oscillator_on_a_spring());
    Inspector inspector(document);
    inspector.show_element("k");
    EXPECT_FALSE(inspector.edit("stiffness", 2e12));
    EXPECT_TRUE(inspector.warning().contains("k.stiffness: must be at most 1e+12 N/m"))
        << inspector.warning().toStdString();
    EXPECT_EQ(get_parameter(document.model(), {"k", "stiffness"}), 100);
    EXPECT_TRUE(inspector.edit("stiffness", 150));
    EXPECT_EQ(get_parameter(document.model(), {"k", "stiffness"}), 150);
    document.undo_stack().undo();
    EXPECT_EQ(get_parameter(document.model(), {"k", "stiffness"}), 100);
    // The margins were probed in the document's model and put back.
    EXPECT_EQ(get_parameter(document.model(), {"a", "mass"}), 0.01);
}

// The bow's module, its contact point and its mass show where the bow meets the string (β), and
// a new β moves the bow to the string mass nearest it in one undoable step, which listeners
// hear as a bow move; a β out of range is refused with the reason and moves nothing. On a
// string in modal form the bow moves along its points.
TEST(Inspector, MovesTheBowAlongTheString) {
    ModelDocument document;
    document.reset(load_model_file(test::resource("models/bowed-string-220.json")));
    Inspector inspector(document);
    for (const char* element : {"friction", "bow_contact", "bow"}) {
        inspector.show_element(element);
        const auto* field = inspector.findChild<QLineEdit*>("bow.position");
        ASSERT_NE(field, nullptr) << element;
        EXPECT_NEAR(QLocale::c().toDouble(field->text()), bow_position(document.model()), 1e-6)
            << element;
    }
    const double before = bow_position(document.model());
    std::vector<ModelDocument::Change> heard;
    QObject::connect(
        &document, &ModelDocument::changed,
        [&](ModelDocument::Change c, const QString&, const QString&) { heard.push_back(c); });
    ASSERT_TRUE(inspector.move_bow(0.3)) << inspector.warning().toStdString();
    const int masses = static_cast<int>(string_masses(document.model()).size());
    const int nearest = static_cast<int>(std::lround(0.3 * (masses + 1)));
    EXPECT_EQ(bow_position(document.model()), static_cast<double>(nearest) / (masses + 1));
    EXPECT_EQ(bowed_centre(document.model(), *document.model().find_lia("friction")),
              "s" + std::to_string(nearest));
    EXPECT_EQ(document.undo_stack().undoText().toStdString(), "Move the bow to β = 0.3");
    // Its drawing went with it: the contact, the bow and the hand's points above the new centre.
    const Model& moved = document.model();
    const double centre_x = moved.find_mat("s" + std::to_string(nearest))->display->first;
    for (const char* part : {"bow_contact", "bow", "hand_slide"})
        EXPECT_EQ(moved.find_mat(part)->display->first, centre_x) << part;
    document.undo_stack().undo();
    EXPECT_EQ(bow_position(document.model()), before);
    EXPECT_EQ(heard, (std::vector{ModelDocument::Change::BowMove, ModelDocument::Change::BowMove}));

    EXPECT_TRUE(inspector.move_bow(before + 0.001)) << "nearest the same mass";
    EXPECT_EQ(document.undo_stack().count(), 1) << "which moves nothing";
    EXPECT_FALSE(inspector.move_bow(0.7));
    EXPECT_TRUE(inspector.warning().contains("β must be in (0, 0.5)"))
        << inspector.warning().toStdString();
    EXPECT_EQ(bow_position(document.model()), before);
    EXPECT_EQ(document.undo_stack().count(), 1);

    BowedStringOptions modal;
    modal.pitch = 220, modal.masses = 40, modal.structure = Structure::Modal;
    document.reset(build_bowed_string(modal));
    inspector.show_element("friction");
    const auto* field = inspector.findChild<QLineEdit*>("bow.position");
    ASSERT_NE(field, nullptr) << "a string in modal form";
    EXPECT_NEAR(QLocale::c().toDouble(field->text()), bow_position(document.model()), 1e-6);
    ASSERT_TRUE(inspector.move_bow(0.3)) << inspector.warning().toStdString();
    const std::string centre = "s" + std::to_string(std::lround(0.3 * (40 + 1)));
    EXPECT_EQ(bowed_centre(document.model(), *document.model().find_lia("friction")), centre);
    EXPECT_EQ(document.model().find_mat("bow_contact")->display->first,
              document.model().find_mat(centre)->display->first);
}

}  // namespace
}  // namespace archet::ui
