// A full-bandwidth string of 220 masses (issue 14) in the studio's editor and panels, under
// Qt's offscreen platform: it opens fitted with every mass in view, zooms in and out with the
// keys and the wheel, pans by dragging the background, and a click selects the element under
// it at every zoom; the window holds all its masses, the modes panel and the string's scope
// take them all.

#include <gtest/gtest.h>

#include <qcustomplot.h>
#include <QApplication>
#include <QScrollBar>
#include <QTest>
#include <QWheelEvent>
#include <set>
#include <string>

#include "archet/files/model_file.hpp"
#include "archet/ipc/segment_layout.hpp"
#include "archet/model/string_points.hpp"
#include "archet/ui/graph_view.hpp"
#include "archet/ui/main_window.hpp"
#include "archet/ui/model_document.hpp"
#include "archet/ui/modes_panel.hpp"
#include "archet/ui/probe_history.hpp"
#include "archet/ui/scope_panel.hpp"
#include "studio_test_support.hpp"
#include "test_support.hpp"

namespace archet::ui {
namespace {

bool is_chain_mass(const std::string& id) {
    return id.size() > 1 && id[0] == 's' &&
           id.find_first_not_of("0123456789", 1) == std::string::npos;
}

// The shipped 110 Hz string stretched to `n` masses in a row 40 apart, as `archet new
// bowed-string` lays them out: the same total mass, springs n/60 times as stiff (a little
// softer, so that 220 masses stay stable at 48 kHz), the bow at the same point of the string.
Model long_string(int n) {
    const Model shipped = load_model_file(test::resource("models/bowed-string-110-paper.json"));
    int n0 = 0;
    for (const Mat& m : shipped.mats) n0 += is_chain_mass(m.id);
    const std::string bowed = "s" + std::to_string(7 * (n + 1) / (n0 + 1));
    Model model = shipped;
    model.name = "bowed-string-long-" + std::to_string(n);
    model.mats.clear(), model.lias.clear();
    Mat mass = *shipped.find_mat("s1");
    mass.mass *= static_cast<double>(n0) / n;
    Lia spring = *shipped.find_lia("k0");
    spring.stiffness *= 0.7 * n / n0;
    const double shift = 40.0 * (std::stoi(bowed.substr(1)) - 7);  // the bow follows its point
    std::vector<std::string> ids{"bridge"};
    model.mats.push_back(*shipped.find_mat("bridge"));
    for (int i = 1; i <= n; ++i) {
        mass.id = "s" + std::to_string(i), mass.display = std::make_pair(40.0 * i, 0.0);
        model.mats.push_back(mass), ids.push_back(mass.id);
    }
    Mat nut = *shipped.find_mat("nut");
    nut.display = std::make_pair(40.0 * (n + 1), 0.0);
    model.mats.push_back(nut), ids.push_back("nut");
    for (Mat m : shipped.mats)
        if (!is_chain_mass(m.id) && m.id != "bridge" && m.id != "nut")
            m.display->first += shift, model.mats.push_back(m);
    for (int i = 0; i <= n; ++i) {
        spring.id = "k" + std::to_string(i), spring.from = ids[i], spring.to = ids[i + 1];
        model.lias.push_back(spring);
    }
    for (Lia l : shipped.lias) {
        if (l.id[0] == 'k' && is_chain_mass("s" + l.id.substr(1))) continue;
        if (l.kind == LiaKind::BowFriction) l.to = bowed;
        model.lias.push_back(l);
    }
    for (Probe& p : model.probes)
        if (p.element == "s7") p.element = bowed;
    return model;
}

class LongChain : public ::testing::Test {
  protected:
    void SetUp() override {
        view.resize(1000, 400);
        view.show();
        ASSERT_TRUE(QTest::qWaitForWindowExposed(&view));
        document.reset(long_string(220));
    }
    QPoint screen_of(const QString& id) { return view.mapFromScene(view.node_position(id)); }
    bool all_masses_in_view() {
        for (const Mat& m : document.model().mats)
            if (!view.viewport()->rect().contains(screen_of(QString::fromStdString(m.id))))
                return false;
        return true;
    }
    void click(QPoint at, Qt::KeyboardModifiers keys = {}) {
        QTest::mouseClick(view.viewport(), Qt::LeftButton, keys, at);
    }

    ModelDocument document;
    GraphView view{document};
};

TEST_F(LongChain, OpensFittedWithTheWholeChainInViewAndNothingToScroll) {
    ASSERT_EQ(document.model().mats.size(), 227u);
    EXPECT_TRUE(view.fitting());
    EXPECT_TRUE(all_masses_in_view());
    EXPECT_EQ(view.horizontalScrollBar()->maximum(), view.horizontalScrollBar()->minimum());
    // The chain spans the width: fitted, not shrunk to a corner.
    EXPECT_GT(screen_of("nut").x() - screen_of("bridge").x(), 0.8 * view.viewport()->width());
    int shown = 0;
    for (const auto* label : view.labels()) shown += label->isVisible();
    EXPECT_GE(shown, 10) << "some ids stay readable on the fitted chain";
    EXPECT_LT(shown, 227) << "too dense to show them all";
}

TEST_F(LongChain, KeysZoomInAndOutAndCtrlZeroFitsAgain) {
    const double fitted = view.zoom();
    QTest::keyClick(&view, Qt::Key_Equal, Qt::ControlModifier);
    EXPECT_NEAR(view.zoom(), 1.25 * fitted, 1e-9 * fitted);
    EXPECT_FALSE(view.fitting());
    for (int i = 0; i < 8; ++i) QTest::keyClick(&view, Qt::Key_Plus, Qt::ControlModifier);
    EXPECT_GT(view.zoom(), 5 * fitted);
    EXPECT_FALSE(all_masses_in_view());
    EXPECT_GT(view.horizontalScrollBar()->maximum(), view.horizontalScrollBar()->minimum())
        << "zoomed in, the scroll bar reaches the rest of the chain";
    const double in = view.zoom();
    QTest::keyClick(&view, Qt::Key_Minus, Qt::ControlModifier);
    EXPECT_NEAR(view.zoom(), in / 1.25, 1e-9 * in);
    QTest::keyClick(&view, Qt::Key_0, Qt::ControlModifier);
    EXPECT_TRUE(view.fitting());
    EXPECT_NEAR(view.zoom(), fitted, 1e-6 * fitted);
    EXPECT_TRUE(all_masses_in_view());
}

TEST_F(LongChain, AClickSelectsTheMassUnderItAtEveryZoom) {
    const double fitted = view.zoom();
    for (const double zoom : {fitted, 3 * fitted, 1.0, 4.0, 0.6 * fitted}) {
        view.zoom_to(zoom);
        for (const char* id : {"s1", "s110", "s219", "nut"}) {
            view.centerOn(view.node_position(id));
            click(screen_of(id));
            EXPECT_EQ(view.selected_ids(), QStringList{id}) << id << " at zoom " << zoom;
        }
    }
    // Fitted, a node is a few pixels across: a click just beside it still picks it.
    view.fit();
    click(screen_of("s100") + QPoint(0, 5));
    EXPECT_EQ(view.selected_ids(), QStringList{"s100"});
    click(screen_of("s120"), Qt::ControlModifier);
    EXPECT_EQ(view.selected_ids(), (QStringList{"s100", "s120"})) << "Ctrl adds to the selection";
    EXPECT_EQ(document.undo_stack().count(), 0) << "a click moves nothing";
}

TEST_F(LongChain, TheWheelZoomsAboutTheMouseAndShiftWheelScrollsAlong) {
    const double fitted = view.zoom();
    const QPoint at = screen_of("s50");
    auto wheel = [&](QPoint delta, Qt::KeyboardModifiers keys) {
        QWheelEvent e(at, view.viewport()->mapToGlobal(at), {}, delta, Qt::NoButton, keys,
                      Qt::NoScrollPhase, false);
        QApplication::sendEvent(view.viewport(), &e);
    };
    wheel({0, 600}, Qt::ControlModifier);
    EXPECT_GT(view.zoom(), 2 * fitted);
    // Along the chain, that is: across it, the short graph stays centred in the view.
    EXPECT_LE(std::abs(screen_of("s50").x() - at.x()), 2) << "s50 stays under the mouse";
    const int before = view.horizontalScrollBar()->value();
    wheel({0, -240}, Qt::ShiftModifier);
    EXPECT_GT(view.horizontalScrollBar()->value(), before) << "Shift+wheel scrolls along";
    for (int i = 0; i < 20; ++i) wheel({0, -1200}, {});
    EXPECT_GE(view.zoom(), 0.4 * fitted) << "zooming out stops a little past the fitted view";
}

TEST_F(LongChain, DraggingTheBackgroundPansAndShiftDragSelects) {
    view.zoom_to(1.0);
    view.centerOn(view.node_position("s110"));
    view.select({"s3"});
    const QPoint empty = view.mapFromScene(view.node_position("s110") + QPointF(0, 60));
    const int before = view.horizontalScrollBar()->value();
    QTest::mousePress(view.viewport(), Qt::LeftButton, {}, empty);
    QTest::mouseMove(view.viewport(), empty - QPoint(60, 0));
    QTest::mouseMove(view.viewport(), empty - QPoint(120, 0));
    QTest::mouseRelease(view.viewport(), Qt::LeftButton, {}, empty - QPoint(120, 0));
    EXPECT_EQ(view.horizontalScrollBar()->value(), before + 120) << "the view followed the mouse";
    EXPECT_EQ(view.selected_ids(), QStringList{"s3"}) << "a pan keeps the selection";
    EXPECT_EQ(document.undo_stack().count(), 0);

    click(empty);
    EXPECT_TRUE(view.selected_ids().isEmpty()) << "a click on the background deselects";

    // Shift+drag across three masses draws the rubber band round them.
    const QPoint from = view.mapFromScene(view.node_position("s110") + QPointF(-20, -20));
    const QPoint to = view.mapFromScene(view.node_position("s112") + QPointF(20, 20));
    QTest::mousePress(view.viewport(), Qt::LeftButton, Qt::ShiftModifier, from);
    QTest::mouseMove(view.viewport(), (from + to) / 2);
    QTest::mouseMove(view.viewport(), to);
    QTest::mouseRelease(view.viewport(), Qt::LeftButton, Qt::ShiftModifier, to);
    QStringList masses;
    for (const QString& id : view.selected_ids())
        if (document.model().find_mat(id.toStdString())) masses << id;
    EXPECT_EQ(masses, (QStringList{"s110", "s111", "s112"}));
}

TEST(LongChainStudio, OpensWithEveryMassInTheEditorAndItsModesListed) {
    MainWindow window(test::editor_alone());
    window.resize(1400, 900);
    window.show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
    const Model model = long_string(220);
    window.open_model(model);
    QTest::qWait(100);
    std::set<std::string> in_editor, expected;
    for (const auto* label : window.graph().labels()) in_editor.insert(label->text().toStdString());
    for (const Mat& m : model.mats) expected.insert(m.id);
    EXPECT_EQ(in_editor, expected);
    EXPECT_TRUE(window.graph().fitting());
    for (const Mat& m : model.mats)
        EXPECT_TRUE(window.graph().viewport()->rect().contains(window.graph().mapFromScene(
            window.graph().node_position(QString::fromStdString(m.id)))))
            << m.id;
    // The modes come from the background: the editor was usable meanwhile.
    ASSERT_TRUE(test::wait_until([&] { return !window.modes().computing(); }, 30000));
    EXPECT_GT(window.modes().mode_count(), 0);
    EXPECT_GT(window.modes().fundamental(), 90);
    EXPECT_LT(window.modes().fundamental(), 110);
}

TEST(LongChainScope, TheStringScopeDrawsEveryMass) {
    ScopePanel scopes;
    scopes.resize(1200, 700);
    std::vector<float> shape(222);
    std::vector<double> along(222);
    for (std::size_t i = 0; i < shape.size(); ++i)
        shape[i] = 1e-3f * std::sin(3.14159f * static_cast<float>(i) / 221.0f),
        along[i] = static_cast<double>(i);
    ProbeHistory history;
    scopes.refresh(history, shape, along, 48000);
    QCustomPlot& plot = scopes.plot(ScopePanel::Scope::Shape);
    EXPECT_EQ(plot.graph(0)->data()->size(), 222);
    EXPECT_LE(plot.xAxis->range().lower, 0);
    EXPECT_GE(plot.xAxis->range().upper, 221);
    EXPECT_GE(plot.yAxis->range().upper, 1.0) << "the middle's 1 mm is in view";
}

// A string longer than the engine's shape frame (ipc::kMaxShapePoints) comes as points spread
// along it: each is drawn where it lies on the string, and the axis runs to the nut.
TEST(LongChainScope, AStringLongerThanAFrameIsDrawnWhereItsPointsLie) {
    ScopePanel scopes;
    scopes.resize(1200, 700);
    constexpr std::size_t kPoints = 1002;  // a 1,000-mass string with its bridge and nut
    const std::vector<std::size_t> drawn = drawn_points(kPoints, ipc::kMaxShapePoints);
    std::vector<float> shape;
    std::vector<double> along;
    for (std::size_t i : drawn)
        along.push_back(static_cast<double>(i)),
            shape.push_back(1e-3f * std::sin(3.14159f * static_cast<float>(i) / (kPoints - 1)));
    ProbeHistory history;
    scopes.refresh(history, shape, along, 48000);
    QCustomPlot& plot = scopes.plot(ScopePanel::Scope::Shape);
    ASSERT_EQ(plot.graph(0)->data()->size(), static_cast<int>(ipc::kMaxShapePoints));
    EXPECT_EQ(plot.graph(0)->data()->at(0)->key, 0.0);
    EXPECT_EQ(plot.graph(0)->data()->at(plot.graph(0)->data()->size() - 1)->key, kPoints - 1.0)
        << "the nut, at its place on the string";
    EXPECT_GE(plot.xAxis->range().upper, kPoints - 1.0);
}

}  // namespace
}  // namespace archet::ui
