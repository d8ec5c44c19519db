// The studio's attack map: computed in the background for the open model, with progress and
// cancel, drawn as the Guettler diagram, and a clicked point's attack played; the Play menu
// opens it beside the playability map. The gesture pad plays a stroke from rest at a chosen
// acceleration, as the map does.

#include <gtest/gtest.h>
#include <qcustomplot.h>

#include <QAction>
#include <QDir>
#include <QElapsedTimer>
#include <QLabel>
#include <QMenuBar>
#include <QProgressBar>
#include <QPushButton>
#include <QTest>

#include "archet/files/model_file.hpp"
#include "archet/ui/attack_figure.hpp"
#include "archet/ui/attack_panel.hpp"
#include "archet/ui/gesture_pad.hpp"
#include "archet/ui/main_window.hpp"
#include "archet/ui/stroke_driver.hpp"
#include "studio_test_support.hpp"
#include "test_support.hpp"

namespace archet::ui {
namespace {

AttackGrid wedge_grid() {
    AttackGrid grid;
    grid.acceleration_min = 8, grid.acceleration_max = 32, grid.acceleration_steps = 3;
    grid.force_min = 0.02, grid.force_max = 0.3, grid.force_steps = 8;
    return grid;
}

TEST(AttackPanelTest, ComputesInTheBackgroundAndPlaysAClickedAttack) {
    const Model model = load_model_file(test::resource("models/bowed-string-220.json"));
    AttackPanel panel(model);
    panel.resize(1000, 800);
    panel.show();
    panel.set_grid(wedge_grid());
    QString error = "not yet";
    QObject::connect(&panel, &AttackPanel::computed, [&](const QString& e) { error = e; });
    panel.compute();
    EXPECT_TRUE(panel.busy());
    ASSERT_TRUE(test::wait_until([&] { return error != "not yet"; }, 300000));
    ASSERT_TRUE(error.isEmpty()) << error.toStdString();
    ASSERT_EQ(panel.points().size(), 24u);
    EXPECT_EQ(panel.findChild<QProgressBar*>()->value(), 24);
    // The diagram holds every attack: one mark per point across its graphs.
    int marks = 0;
    auto& plot = panel.figure().plot();
    for (int g = 0; g < plot.graphCount(); ++g) marks += plot.graph(g)->data()->size();
    EXPECT_EQ(marks, 24);
    const auto perfect = std::count_if(panel.points().begin(), panel.points().end(), [](auto& p) {
        return p.transient.kind == AttackKind::Perfect;
    });
    EXPECT_GE(perfect, 1) << "the shipped string's wedge crosses this grid";
    QDir().mkpath(ARCHET_ARTIFACT_DIR);
    EXPECT_TRUE(panel.grab().save(QDir(ARCHET_ARTIFACT_DIR).filePath("studio-attack.png")));
    // A click on a point plays its attack, and says what it was.
    const AttackPoint& p = panel.points()[5];
    const QPoint pixel(static_cast<int>(plot.xAxis->coordToPixel(p.acceleration)),
                       static_cast<int>(plot.yAxis->coordToPixel(p.force)));
    EXPECT_EQ(panel.figure().point_at(pixel), 5);
    panel.listen(5);
    EXPECT_TRUE(test::wait_until([&] { return panel.player().position() > 1000u; }, 60000));
    panel.player().stop();
    // While another grid computes, a click still plays the point the figure shows.
    AttackGrid other = wedge_grid();
    other.acceleration_min = 2, other.acceleration_steps = 30, other.force_steps = 30;
    panel.set_grid(other);
    error = "not yet";
    panel.compute();
    ASSERT_TRUE(panel.busy());
    panel.listen(5);
    bool shown_point = false;
    for (const QLabel* label : panel.findChildren<QLabel*>())
        shown_point =
            shown_point ||
            label->text().startsWith(QString("%1 m/s², %2 N:").arg(p.acceleration).arg(p.force));
    EXPECT_TRUE(shown_point) << "point 5 of the grid drawn, not of the one computing";
    panel.player().stop();
    panel.cancel();
    ASSERT_TRUE(test::wait_until([&] { return error != "not yet"; }, 300000));
}

TEST(AttackPanelTest, ACancelStopsTheSweepAndSaysSo) {
    const Model model = load_model_file(test::resource("models/bowed-string-110.json"));
    AttackPanel panel(model);
    AttackGrid grid = wedge_grid();
    grid.acceleration_steps = 40, grid.force_steps = 40;
    panel.set_grid(grid);
    QString error = "not yet";
    QObject::connect(&panel, &AttackPanel::computed, [&](const QString& e) { error = e; });
    panel.compute();
    panel.cancel();
    ASSERT_TRUE(test::wait_until([&] { return error != "not yet"; }, 300000));
    EXPECT_TRUE(error.contains("cancelled")) << error.toStdString();
    EXPECT_TRUE(panel.points().empty());
    EXPECT_FALSE(panel.busy());
}

TEST(AttackPanelTest, ThePlayMenuOpensItBesideThePlayabilityMap) {
    MainWindow window(test::editor_alone());
    QAction* attack = nullptr;
    for (QAction* menu : window.menuBar()->actions())
        for (QAction* a : menu->menu() ? menu->menu()->actions() : QList<QAction*>{})
            if (a->text().remove('&') == "Attack map…") attack = a;
    ASSERT_NE(attack, nullptr);
    EXPECT_EQ(attack->shortcut(), QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_M));
    attack->trigger();
    QTest::qWait(50);
    EXPECT_NE(window.findChild<AttackPanel*>(), nullptr);
}

TEST(StrokeDriverTest, SlidesFromRestWithTheChosenAccelerationToTheEdge) {
    GesturePad pad;
    pad.resize(420, 260);
    pad.show();
    pad.set_position(-0.1, 0.002);
    StrokeDriver stroke(pad);
    struct Seen {
        double t, slide, press;
    };
    std::vector<Seen> seen;
    QElapsedTimer clock;
    QObject::connect(&pad, &GesturePad::moved, [&](double slide, double press) {
        seen.push_back({static_cast<double>(clock.nsecsElapsed()) * 1e-9, slide, press});
    });
    bool finished = false;
    QObject::connect(&stroke, &StrokeDriver::finished, [&] { finished = true; });
    clock.start();
    stroke.start(8.0);
    ASSERT_TRUE(stroke.running());
    ASSERT_TRUE(test::wait_until([&] { return finished; }, 60000));
    EXPECT_FALSE(stroke.running());
    ASSERT_GE(seen.size(), 3u);
    EXPECT_EQ(seen.back().slide, GesturePad::kSlideRange) << "to the far edge, and no further";
    // The bow was never ahead of ½·a·t² from rest (a position is computed before it is seen),
    // it never went back, and the press held.
    for (std::size_t i = 0; i < seen.size(); ++i) {
        EXPECT_LE(seen[i].slide, -0.1 + 0.5 * 8.0 * seen[i].t * seen[i].t + 1e-9) << i;
        if (i > 0) EXPECT_GE(seen[i].slide, seen[i - 1].slide) << i;
        EXPECT_EQ(seen[i].press, 0.002);
    }
    EXPECT_GE(seen.back().t, std::sqrt(2 * 0.25 / 8.0)) << "0.25 m from rest at 8 m/s²";
    // Taking the bow with the mouse stops a stroke.
    pad.set_position(-0.1, 0.002);
    finished = false;
    stroke.start(0.5);
    QTest::mousePress(&pad, Qt::LeftButton, {}, QPoint(20, 60));
    EXPECT_TRUE(finished);
    EXPECT_FALSE(stroke.running());
}

TEST(StrokeDriverTest, TheStudiosStrokeButtonPlaysOneOnThePad) {
    MainWindow window(test::editor_alone());
    window.resize(1400, 900);
    window.show();
    auto* button = window.findChild<QPushButton*>("stroke");
    ASSERT_NE(button, nullptr);
    window.pad().set_position(0.05, 0.001);
    button->click();
    EXPECT_TRUE(window.stroke().running());
    EXPECT_EQ(button->text(), "Stop");
    ASSERT_TRUE(test::wait_until([&] { return !window.stroke().running(); }, 60000));
    EXPECT_EQ(window.pad().slide(), -GesturePad::kSlideRange) << "from the right, to the left";
    EXPECT_EQ(button->text(), "Stroke");
    QDir().mkpath(ARCHET_ARTIFACT_DIR);
    EXPECT_TRUE(window.grab().save(QDir(ARCHET_ARTIFACT_DIR).filePath("studio-stroke.png")));
}

}  // namespace
}  // namespace archet::ui
