// The studio's attack map: computed in the background for the open model, with progress and
// cancel, drawn as the Guettler diagram, and a clicked point's attack played; the Play menu
// opens it as a tab beside the playability map's. The gesture pad plays a stroke from rest at a
// chosen acceleration, as the map does.

#include <gtest/gtest.h>
#include <qcustomplot.h>

#include <QAction>
#include <QDir>
#include <QElapsedTimer>
#include <QLabel>
#include <QMenuBar>
#include <QProgressBar>
#include <QPushButton>
#include <QTabWidget>
#include <QTest>

#include "archet/files/model_file.hpp"
#include "archet/ui/attack_figure.hpp"
#include "archet/ui/attack_panel.hpp"
#include "archet/ui/bowing_maps_window.hpp"
#include "archet/ui/gesture_pad.hpp"
#include "archet/ui/main_window.hpp"
#include "archet/ui/model_document.hpp"
#include "archet/ui/stroke_driver.hpp"
#include "studio_test_support.hpp"
#include "test_support.hpp"

namespace archet::ui {
namespace {

AttackGrid wedge_grid() {
    AttackGrid grid;
    grid.acceleration_min = 10, grid.acceleration_max = 20, grid.acceleration_steps = 3;
    grid.force_min = 1.5, grid.force_max = 3.2, grid.force_steps = 8;
    grid.log_axes = false;
    return grid;
}

TEST(AttackPanelTest, ComputesInTheBackgroundAndPlaysAClickedAttack) {
    const Model model = load_model_file(test::resource("models/bowed-string-220.json"));
    BowingMapsWindow maps(model, {});
    maps.resize(1000, 860);
    maps.show_tab(BowingMapsWindow::Tab::Attack);
    AttackPanel& panel = maps.attack();
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
    EXPECT_TRUE(maps.grab().save(QDir(ARCHET_ARTIFACT_DIR).filePath("studio-attack.png")));
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
            label->text().startsWith(
                QString("%1 m/s², %2 N:").arg(p.acceleration, 0, 'g', 3).arg(p.force, 0, 'g', 3));
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

QAction* play_menu_action(MainWindow& window, const QString& text) {
    for (QAction* menu : window.menuBar()->actions())
        for (QAction* a : menu->menu() ? menu->menu()->actions() : QList<QAction*>{})
            if (a->text().remove('&') == text) return a;
    return nullptr;
}

// One attack at 20 m/s² and 3 N: inside the 220 Hz string's wedge of perfect attacks, under the
// 110 Hz string's (whose attack there begins with extra slips).
AttackGrid one_attack() {
    AttackGrid grid;
    grid.acceleration_min = grid.acceleration_max = 20, grid.acceleration_steps = 1;
    grid.force_min = grid.force_max = 3, grid.force_steps = 1;
    grid.log_axes = false;
    return grid;
}

QString message_of(const AttackPanel& panel) {
    // The panel's message is its only word-wrapped label.
    for (const QLabel* label : panel.findChildren<QLabel*>())
        if (label->wordWrap()) return label->text();
    return {};
}

AttackKind compute_one_attack(AttackPanel& panel) {
    QString error = "not yet";
    auto seen =
        QObject::connect(&panel, &AttackPanel::computed, [&](const QString& e) { error = e; });
    panel.set_grid(one_attack());
    panel.compute();
    EXPECT_TRUE(test::wait_until([&] { return error != "not yet"; }, 300000));
    QObject::disconnect(seen);
    EXPECT_TRUE(error.isEmpty()) << error.toStdString();
    return panel.points().empty() ? AttackKind::Never : panel.points().front().transient.kind;
}

TEST(AttackPanelTest, ThePlayMenuOpensTheAttackTabBesideThePlayabilityTab) {
    MainWindow window(test::editor_alone());
    window.open_model(load_model_file(test::resource("models/bowed-string-220.json")));
    QAction* attack = play_menu_action(window, "Attack map…");
    QAction* playability = play_menu_action(window, "Playability map…");
    ASSERT_NE(attack, nullptr);
    ASSERT_NE(playability, nullptr);
    EXPECT_EQ(attack->shortcut(), QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_M));
    EXPECT_EQ(playability->shortcut(), QKeySequence(Qt::CTRL | Qt::Key_M));
    attack->trigger();
    auto* maps = window.findChild<BowingMapsWindow*>();
    ASSERT_NE(maps, nullptr);
    EXPECT_TRUE(maps->isVisible());
    EXPECT_EQ(maps->current_tab(), BowingMapsWindow::Tab::Attack);
    auto* tabs = maps->findChild<QTabWidget*>();
    ASSERT_NE(tabs, nullptr);
    ASSERT_EQ(tabs->count(), 2);
    EXPECT_EQ(tabs->tabText(0), "Playability");
    EXPECT_EQ(tabs->tabText(1), "Attack");
    EXPECT_TRUE(maps->windowTitle().contains("bowed-string-220"));

    EXPECT_EQ(compute_one_attack(maps->attack()), AttackKind::Perfect);
    // A grid of one point is drawn around it (its axes had no span to fit).
    QCustomPlot& plot = maps->attack().figure().plot();
    EXPECT_TRUE(plot.xAxis->range().contains(20.0) && plot.xAxis->range().size() > 0.1);
    EXPECT_TRUE(plot.yAxis->range().contains(3.0) && plot.yAxis->range().size() > 0.01);
    maps->resize(1000, 860);
    QDir().mkpath(ARCHET_ARTIFACT_DIR);
    EXPECT_TRUE(maps->grab().save(QDir(ARCHET_ARTIFACT_DIR).filePath("studio-bowing-maps.png")));

    // The other map is the other tab of the same window.
    playability->trigger();
    EXPECT_EQ(window.findChildren<BowingMapsWindow*>().size(), 1);
    EXPECT_EQ(maps->current_tab(), BowingMapsWindow::Tab::Playability);
    // Closed and opened again, the window keeps the map it computed.
    maps->close();
    attack->trigger();
    EXPECT_EQ(window.findChild<BowingMapsWindow*>(), maps);
    EXPECT_TRUE(maps->isVisible());
    EXPECT_EQ(maps->attack().points().size(), 1u);

    // Another model opened: the window follows it; the map shown says it is the old model's
    // until Compute maps the new one.
    window.open_model(load_model_file(test::resource("models/bowed-string-110.json")));
    EXPECT_TRUE(maps->windowTitle().contains("bowed-string-110"));
    EXPECT_TRUE(message_of(maps->attack()).startsWith("The model has changed since this map"));
    // A click still plays the attack the map shows: the 220 Hz string's, perfect.
    maps->attack().listen(0);
    maps->attack().player().stop();
    EXPECT_TRUE(message_of(maps->attack()).startsWith("20 m/s², 3 N: perfect"))
        << message_of(maps->attack()).toStdString();
    EXPECT_TRUE(message_of(maps->attack()).contains("The model has changed since this map"));
    EXPECT_NE(compute_one_attack(maps->attack()), AttackKind::Perfect)
        << "the 110 Hz string's attack at 3 N and 20 m/s² begins with extra slips";
    EXPECT_FALSE(message_of(maps->attack()).contains("The model has changed"));
    // Moving an element on the canvas changes no physics: the map stays the model's.
    const QString mass = QString::fromStdString(window.document().model().mats.front().id);
    window.document().move({mass}, QPointF(10, 10), false);
    EXPECT_FALSE(message_of(maps->attack()).contains("The model has changed"));
}

TEST(AttackPanelTest, AMapComputedWhileTheModelChangedSaysSoAndClosingStopsASweep) {
    const Model model = load_model_file(test::resource("models/bowed-string-220.json"));
    BowingMapsWindow maps(model, {});
    maps.show_tab(BowingMapsWindow::Tab::Attack);
    AttackPanel& panel = maps.attack();
    QString error = "not yet";
    QObject::connect(&panel, &AttackPanel::computed, [&](const QString& e) { error = e; });
    panel.set_grid(one_attack());
    panel.compute();
    maps.set_model(load_model_file(test::resource("models/bowed-string-110.json")));
    ASSERT_TRUE(test::wait_until([&] { return error != "not yet"; }, 300000));
    EXPECT_TRUE(message_of(panel).contains("The model has changed since this map"))
        << "an edit during the sweep: the map is of the model before it";
    // Closing the window stops a sweep under way; the window and its last map stay.
    AttackGrid large = one_attack();
    large.acceleration_steps = large.force_steps = 60;
    large.acceleration_max = 40, large.force_max = 6;
    panel.set_grid(large);
    error = "not yet";
    panel.compute();
    ASSERT_TRUE(panel.busy());
    maps.close();
    ASSERT_TRUE(test::wait_until([&] { return error != "not yet"; }, 300000));
    EXPECT_TRUE(error.contains("cancelled")) << error.toStdString();
    EXPECT_EQ(panel.points().size(), 1u);
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
        if (i > 0) {
            EXPECT_GE(seen[i].slide, seen[i - 1].slide) << i;
        }
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
