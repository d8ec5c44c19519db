// The studio's attack map: computed in the background for the open model, with progress and
// cancel, drawn as the Guettler diagram, and a clicked point's attack played; the Play menu
// opens it beside the playability map.

#include <gtest/gtest.h>
#include <qcustomplot.h>

#include <QAction>
#include <QDir>
#include <QMenuBar>
#include <QProgressBar>
#include <QTest>

#include "archet/files/model_file.hpp"
#include "archet/ui/attack_figure.hpp"
#include "archet/ui/attack_panel.hpp"
#include "archet/ui/main_window.hpp"
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

}  // namespace
}  // namespace archet::ui
