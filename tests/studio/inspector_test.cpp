// The inspector reads the parameter table: each field says its unit and range, shows a
// stability margin only for what the bound depends on, and an edit is checked once by the
// document, which undoes to the value it replaced.

#include <gtest/gtest.h>

#include <QLabel>
#include <QLineEdit>

#include "archet/model/model_parameters.hpp"
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

}  // namespace
}  // namespace archet::ui
