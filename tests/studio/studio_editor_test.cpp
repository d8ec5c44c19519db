// The studio's model editor under Qt's offscreen platform: placing, connecting, moving,
// deleting, copying and pasting elements on the canvas, each undone and redone exactly; a
// model edited in the editor saves and reloads identically; the inspector refuses a value
// that would make the scheme unstable and says why; the modes panel finds the string's. What
// the studio shows stays readable: scope axes that do not magnify round-off, a spectrum that
// resolves the lowest string's partials and says how finely, frequencies in plain hertz,
// regimes and messages in words, pastes beside their originals, labels at a readable size.

#include <gtest/gtest.h>

#include <qcustomplot.h>
#include <QApplication>
#include <QDir>
#include <QGraphicsView>
#include <QHeaderView>
#include <QLabel>
#include <QScrollBar>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTableWidget>
#include <QTest>
#include <QWheelEvent>
#include <cmath>
#include <numbers>
#include <set>

#include "archet/analysis/modal_analysis.hpp"
#include "archet/builders/bowed_string.hpp"
#include "archet/common/input_error.hpp"
#include "archet/files/model_file.hpp"
#include "archet/model/model_parameters.hpp"
#include "archet/ui/compare_figure.hpp"
#include "archet/ui/compare_view.hpp"
#include "archet/ui/gesture_pad.hpp"
#include "archet/ui/graph_view.hpp"
#include "archet/ui/inspector.hpp"
#include "archet/ui/main_window.hpp"
#include "archet/ui/model_document.hpp"
#include "archet/ui/modes_panel.hpp"
#include "archet/ui/new_string_dialog.hpp"
#include "archet/ui/playability_figure.hpp"
#include "archet/ui/playability_panel.hpp"
#include "archet/ui/probe_history.hpp"
#include "archet/ui/scope_panel.hpp"
#include "studio_test_support.hpp"
#include "test_support.hpp"

namespace archet::ui {
namespace {

std::string text_of(const Model& m) {
    return format_model(m);
}

// A small editable model: two masses on a spring between fixed ends.
Model little_model() {
    Model m;
    m.name = "little";
    m.mats = {test::fixed("left"), test::mass("a", 0.01), test::mass("b", 0.01),
              test::fixed("right")};
    for (std::size_t i = 0; i < m.mats.size(); ++i)
        m.mats[i].display = std::make_pair(100.0 * static_cast<double>(i), 0.0);
    m.lias = {test::spring_damper("k1", "left", "a", 100, 0.01),
              test::spring_damper("k2", "a", "b", 100, 0.01),
              test::spring_damper("k3", "b", "right", 100, 0.01)};
    m.outputs = {{"a", Output::Signal::Position, 1.0}};
    return m;
}

class Editor : public ::testing::Test {
  protected:
    void SetUp() override {
        document.reset(little_model());
        view.resize(800, 400);
        view.show();
        view.fit();
    }
    QPoint screen_of(const QString& id) { return view.mapFromScene(view.node_position(id)); }
    QPoint screen_at(QPointF scene) { return view.mapFromScene(scene); }

    ModelDocument document;
    GraphView view{document};
};

TEST_F(Editor, PlacingConnectingMovingAndDeletingAreEachUndoable) {
    const std::string original = text_of(document.model());
    std::vector<std::string> after_each;

    view.set_tool(GraphView::Tool::AddMat, MatKind::Mass);
    QTest::mouseClick(view.viewport(), Qt::LeftButton, {}, screen_at({150, 120}));
    ASSERT_EQ(document.model().mats.size(), 5u) << "a mass placed where clicked";
    const Mat& added = document.model().mats.back();
    EXPECT_NEAR(added.display->first, 150, 2);
    EXPECT_NEAR(added.display->second, 120, 2);
    const QString m1 = QString::fromStdString(added.id);
    after_each.push_back(text_of(document.model()));

    view.set_tool(GraphView::Tool::Connect, MatKind::Mass, LiaKind::Spring);
    QTest::mousePress(view.viewport(), Qt::LeftButton, {}, screen_of("b"));
    QTest::mouseMove(view.viewport(), screen_of(m1));
    QTest::mouseRelease(view.viewport(), Qt::LeftButton, {}, screen_of(m1));
    ASSERT_EQ(document.model().lias.size(), 4u) << "dragging from b to the new mass joins them";
    EXPECT_EQ(document.model().lias.back().from, "b");
    EXPECT_EQ(QString::fromStdString(document.model().lias.back().to), m1);
    after_each.push_back(text_of(document.model()));

    view.set_tool(GraphView::Tool::Select);
    document.move({m1}, {30, -10}, false);
    EXPECT_NEAR(document.model().find_mat(m1.toStdString())->display->first, 180, 2);
    after_each.push_back(text_of(document.model()));

    view.select({m1});
    QTest::keyClick(view.viewport(), Qt::Key_Delete);
    EXPECT_EQ(document.model().mats.size(), 4u);
    EXPECT_EQ(document.model().lias.size(), 3u) << "its link goes with it";
    after_each.push_back(text_of(document.model()));

    // Back to the start one step at a time, then forward again.
    for (int i = static_cast<int>(after_each.size()) - 2; i >= -1; --i) {
        document.undo_stack().undo();
        EXPECT_EQ(text_of(document.model()), i >= 0 ? after_each[i] : original) << "undo " << i;
    }
    for (const std::string& expected : after_each) {
        document.undo_stack().redo();
        EXPECT_EQ(text_of(document.model()), expected);
    }
}

TEST_F(Editor, DraggingANodeMovesItInOneStep) {
    const QPoint from = screen_of("a");
    const QPoint to = from + QPoint(40, 30);
    QTest::mousePress(view.viewport(), Qt::LeftButton, {}, from);
    for (int i = 1; i <= 4; ++i) QTest::mouseMove(view.viewport(), from + (to - from) * i / 4);
    QTest::mouseRelease(view.viewport(), Qt::LeftButton, {}, to);
    const QPointF moved = view.mapToScene(to) - view.mapToScene(from);
    EXPECT_NEAR(document.model().find_mat("a")->display->first, 100 + moved.x(), 1.0);
    EXPECT_NEAR(document.model().find_mat("a")->display->second, moved.y(), 1.0);
    EXPECT_EQ(document.undo_stack().count(), 1);
    document.undo_stack().undo();
    EXPECT_NEAR(document.model().find_mat("a")->display->first, 100, 1e-9);
}

TEST_F(Editor, ADragsMovesMergeIntoOneStep) {
    document.move({"a"}, {5, 0}, true);
    document.move({"a"}, {5, 0}, true);
    document.move({"a"}, {5, 0}, true);
    EXPECT_EQ(document.undo_stack().count(), 1);
    EXPECT_NEAR(document.model().find_mat("a")->display->first, 115, 1e-9);
    document.undo_stack().undo();
    EXPECT_NEAR(document.model().find_mat("a")->display->first, 100, 1e-9);
}

TEST_F(Editor, CopyAndPasteDuplicateMassesAndTheLinksAmongThem) {
    const QString copied = document.copy({"a", "b", "k2"});
    const QStringList added = document.paste(copied, {0, 80});
    EXPECT_EQ(added.size(), 3) << added.join(",").toStdString();
    EXPECT_EQ(document.model().mats.size(), 6u);
    EXPECT_EQ(document.model().lias.size(), 4u);
    const Lia& pasted = document.model().lias.back();
    EXPECT_EQ(pasted.from, "a_2");
    EXPECT_EQ(pasted.to, "b_2");
    EXPECT_NEAR(document.model().find_mat("a_2")->display->second, 80, 1e-9);
    EXPECT_TRUE(document.paste("not a model", {}).isEmpty()) << "foreign clipboard text is ignored";
    document.undo_stack().undo();
    EXPECT_EQ(text_of(document.model()), text_of(little_model()));
}

TEST_F(Editor, UndoTextsCountElementsInWords) {
    document.paste(document.copy({"a"}), {0, 80});
    EXPECT_EQ(document.undo_stack().text(document.undo_stack().count() - 1), "Paste 1 element");
    document.paste(document.copy({"a", "b", "k2"}), {0, 160});
    EXPECT_EQ(document.undo_stack().text(document.undo_stack().count() - 1), "Paste 3 elements");
    document.remove({"a_2", "b_2"});
    EXPECT_EQ(document.undo_stack().text(document.undo_stack().count() - 1), "Delete 2 elements");
}

TEST_F(Editor, ARefusedValueReadsAsASentence) {
    Inspector inspector(document);
    inspector.show_element("a");
    EXPECT_FALSE(inspector.edit("mass", 0));
    const std::string said = inspector.warning().toStdString();
    EXPECT_NE(said.find("a.mass: must be above 0 kg (is 0)"), std::string::npos) << said;
    EXPECT_EQ(said.find("0.000000"), std::string::npos) << said;
    Model model = little_model();
    try {
        set_parameter(model, {"k1", "damping"}, -0.25);
        ADD_FAILURE() << "a negative damping is refused";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("must be at least 0 N·s/m (is -0.25)"),
                  std::string::npos)
            << e.what();
    }
}

// The shipped 110 Hz string as a model that has never been drawn: no display positions.
Model undrawn_long_string() {
    Model m = load_model_file(test::resource("models/bowed-string-110.json"));
    for (Mat& mat : m.mats) mat.display.reset();
    return m;
}

TEST(PasteTest, PastedElementsLandNextToTheOriginalsAndNotOnAnEarlierPaste) {
    ModelDocument document;
    document.reset(undrawn_long_string());
    const QStringList originals{"s30", "s31"};
    const QString copied = document.copy(originals);
    const QStringList first = document.paste(copied, {40, 40});
    const QStringList second = document.paste(copied, {40, 40});
    // The two masses, then the link between them.
    ASSERT_EQ(first.size(), 3) << first.join(",").toStdString();
    ASSERT_EQ(second.size(), 3) << second.join(",").toStdString();
    const auto& model = document.model();
    auto at = [&](const QString& id) {
        return document.position_of(*model.find_mat(id.toStdString()));
    };
    for (int i = 0; i < 2; ++i) {
        const QPointF original = at(originals[i]);
        EXPECT_LT(QLineF(at(first[i]), original).length(), 100)
            << first[i].toStdString() << " beside " << originals[i].toStdString();
        EXPECT_LT(QLineF(at(second[i]), original).length(), 200);
        EXPECT_GT(QLineF(at(second[i]), at(first[i])).length(), 20)
            << "a second paste is not drawn over the first";
    }
}

// A view that fits itself must settle: scroll bars that appeared and vanished as it refitted
// resized its viewport again and again (the studio froze for seconds on the 440 Hz string).
TEST(GraphLabelsTest, FittingAModelSettlesAtOnce) {
    MainWindow window(test::editor_alone());
    window.resize(1400, 900);
    window.show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
    struct ResizeCounter : QObject {
        int resizes = 0;
        bool eventFilter(QObject*, QEvent* e) override {
            if (e->type() == QEvent::Resize) ++resizes;
            return false;
        }
    } counter;
    window.graph().viewport()->installEventFilter(&counter);
    for (const char* name : {"bowed-string-110", "bowed-string-440", "bowed-string-880"}) {
        counter.resizes = 0;
        window.open_model(load_model_file(test::resource(std::string("models/") + name + ".json")));
        QTest::qWait(300);
        EXPECT_LE(counter.resizes, 2) << name;
    }
    window.graph().viewport()->removeEventFilter(&counter);
}

TEST(GraphLabelsTest, ALongStringFitsWithReadableLabelsAndZoomingInShowsThemAll) {
    ModelDocument document;
    GraphView view(document);
    view.resize(800, 400);
    view.show();
    document.reset(load_model_file(test::resource("models/bowed-string-110-paper.json")));
    view.fit();
    ASSERT_GT(document.model().mats.size(), 60u);
    ASSERT_EQ(view.labels().size(), document.model().mats.size());

    auto on_screen_font_pixels = [&](const QGraphicsSimpleTextItem& label) {
        const double scale = view.label_on_screen(label).height() / label.boundingRect().height();
        return QFontInfo(label.font()).pixelSize() * scale;
    };
    auto shown = [&] {
        std::vector<const QGraphicsSimpleTextItem*> visible;
        for (const auto* label : view.labels())
            if (label->isVisible()) visible.push_back(label);
        return visible;
    };
    auto expect_readable_and_apart = [&](const char* when) {
        const auto visible = shown();
        for (std::size_t i = 0; i < visible.size(); ++i) {
            EXPECT_GE(on_screen_font_pixels(*visible[i]), 8) << when;
            for (std::size_t j = i + 1; j < visible.size(); ++j)
                EXPECT_FALSE(
                    view.label_on_screen(*visible[i]).intersects(view.label_on_screen(*visible[j])))
                    << when << ": " << visible[i]->text().toStdString() << " over "
                    << visible[j]->text().toStdString();
        }
    };
    expect_readable_and_apart("fitted");
    QDir().mkpath(ARCHET_ARTIFACT_DIR);
    EXPECT_TRUE(view.grab().save(QDir(ARCHET_ARTIFACT_DIR).filePath("studio-graph-fitted.png")));
    EXPECT_GE(shown().size(), 5u) << "some labels stay on a fitted long string";
    EXPECT_LT(shown().size(), view.labels().size()) << "too dense to show all at once";

    // A selected node shows its id even where labels were thinned out.
    const QGraphicsSimpleTextItem* hidden = nullptr;
    for (const auto* label : view.labels())
        if (!label->isVisible()) hidden = label;
    ASSERT_NE(hidden, nullptr);
    view.select({hidden->text()});
    EXPECT_TRUE(hidden->isVisible());
    view.select({});

    // The wheel zooms in on the middle: every node in view then has its label.
    const QPointF middle = view.viewport()->rect().center();
    QWheelEvent wheel(middle, view.viewport()->mapToGlobal(middle), {}, {0, 1200}, Qt::NoButton,
                      Qt::NoModifier, Qt::NoScrollPhase, false);
    QApplication::sendEvent(view.viewport(), &wheel);
    expect_readable_and_apart("zoomed in");
    auto expect_every_node_in_view_labelled = [&](const char* when) {
        int in_view = 0;
        for (const auto* label : view.labels()) {
            const QPoint node = view.mapFromScene(label->parentItem()->scenePos());
            if (!view.viewport()->rect().contains(node)) continue;
            ++in_view;
            EXPECT_TRUE(label->isVisible()) << when << ": " << label->text().toStdString();
        }
        EXPECT_GE(in_view, 3) << when;
    };
    expect_every_node_in_view_labelled("zoomed in");
    EXPECT_TRUE(view.grab().save(QDir(ARCHET_ARTIFACT_DIR).filePath("studio-graph-zoomed.png")));

    // Scrolled to the nut: the labels there, off screen until now, are placed and shown.
    view.horizontalScrollBar()->setValue(view.horizontalScrollBar()->maximum());
    QApplication::processEvents();
    expect_readable_and_apart("scrolled");
    expect_every_node_in_view_labelled("scrolled");
}

// No id label covers another node: the body's modes hang in a column under the bridge, where
// labels under their nodes would hide them (and the nodes the labels: "bridge" read "cridge"),
// so those stand beside their nodes. The bridge keeps its label.
TEST(GraphLabelsTest, NoLabelCoversAnotherNode) {
    ModelDocument document;
    GraphView view(document);
    view.resize(1100, 200);  // about as wide as the studio's graph
    view.show();
    document.reset(load_model_file(test::resource("models/bowed-string-220.json")));
    view.fit();
    QApplication::processEvents();
    std::vector<QRectF> nodes;
    for (const auto* label : view.labels())
        nodes.push_back(view.mapFromScene(label->parentItem()->sceneBoundingRect())
                            .boundingRect()
                            .adjusted(2, 2, -2, -2));  // its rim, which a label may touch
    bool bridge_labelled = false;
    int beside = 0;
    for (const auto* label : view.labels()) {
        if (!label->isVisible()) continue;
        bridge_labelled = bridge_labelled || label->text() == "bridge";
        const QRectF box = view.label_on_screen(*label);
        beside += box.top() < view.mapFromScene(label->parentItem()->scenePos()).y();
        for (std::size_t n = 0; n < nodes.size(); ++n) {
            if (view.labels()[n] == label) continue;
            EXPECT_FALSE(box.intersects(nodes[n])) << label->text().toStdString() << " covers "
                                                   << view.labels()[n]->text().toStdString();
        }
    }
    EXPECT_TRUE(bridge_labelled);
    EXPECT_GT(beside, 0) << "some stand beside their nodes";
    QDir().mkpath(ARCHET_ARTIFACT_DIR);
    EXPECT_TRUE(view.grab().save(QDir(ARCHET_ARTIFACT_DIR).filePath("studio-graph-body.png")));
}

// A MAT of a slower level hemmed in below and beside by other nodes stands its id above it;
// its rate badge then stands over the id, rather than hidden under it.
TEST(GraphLabelsTest, ARateBadgeStandsOverAnIdThatTookThePlaceAbove) {
    auto mass = [](const char* id, const char* rate, double x, double y) {
        return std::string(R"({"id": ")") + id + R"(", "type": "mass", "rate": ")" + rate +
               R"(", "mass": 0.001, "display": [)" + std::to_string(x) + ", " + std::to_string(y) +
               "]}";
    };
    const std::string text =
        R"({"format": "archet-model", "version": 1, "sample_rate": 48000,
            "rates": [{"id": "audio", "divider": 1}, {"id": "haptic", "divider": 16}],
            "masses": [)" +
        mass("hemmed", "haptic", 0, 0) + "," + mass("under", "audio", 0, 22) + "," +
        mass("left", "audio", -22, 0) + "," + mass("right", "audio", 22, 0) + "," +
        mass("far_left", "audio", -400, 0) + "," + mass("far_right", "audio", 400, 0) +
        R"(], "links": [], "outputs": [{"element": "under", "signal": "position"}]})";
    ModelDocument document;
    GraphView view(document);
    view.resize(900, 300);
    view.show();
    document.reset(parse_model(text));
    view.fit();
    QApplication::processEvents();
    ASSERT_NEAR(view.zoom(), 1.0, 0.6) << "the far nodes keep the fitted view near one to one";
    const QGraphicsSimpleTextItem* id = nullptr;
    for (const auto* label : view.labels())
        if (label->text() == "hemmed") id = label;
    ASSERT_NE(id, nullptr);
    ASSERT_TRUE(id->isVisible());
    const QRectF id_box = view.label_on_screen(*id);
    const QPointF node = view.mapFromScene(id->parentItem()->scenePos());
    ASSERT_LT(id_box.bottom(), node.y()) << "hemmed in below and beside, the id stands above";
    ASSERT_EQ(view.badges().size(), 1u);
    const QGraphicsSimpleTextItem& badge = *view.badges()[0];
    EXPECT_EQ(badge.text(), "haptic");
    EXPECT_TRUE(badge.isVisible());
    const QRectF badge_box = view.label_on_screen(badge);
    EXPECT_FALSE(badge_box.intersects(id_box));
    EXPECT_LE(badge_box.bottom(), id_box.top() + 0.5) << "the badge stands over the id";
    EXPECT_NEAR(badge_box.center().x(), node.x(), 1.0);
    QDir().mkpath(ARCHET_ARTIFACT_DIR);
    EXPECT_TRUE(view.grab().save(QDir(ARCHET_ARTIFACT_DIR).filePath("studio-graph-badge.png")));
}

TEST_F(Editor, AnEditedModelSavesAndReloadsIdentically) {
    document.add_mat(MatKind::Oscillator, {50, 60});
    document.edit_parameter({"k2", "stiffness"}, 250);
    const auto dir = test::temp_dir("editor-save");
    write_file_atomically(dir / "edited.json", format_model(document.model()));
    const Model reloaded = load_model_file(dir / "edited.json");
    EXPECT_EQ(text_of(reloaded), text_of(document.model()));
    EXPECT_EQ(reloaded.find_lia("k2")->stiffness, 250);
}

TEST_F(Editor, TheInspectorRefusesAnUnstableValueAndSaysWhy) {
    Inspector inspector(document);
    inspector.show_element("k2");
    EXPECT_TRUE(inspector.edit("stiffness", 300));
    EXPECT_EQ(document.model().find_lia("k2")->stiffness, 300);
    const std::string before = text_of(document.model());
    // At 48 kHz two 10 g masses go unstable near K = 0.01·(2·48000)²/4 ≈ 2.3e7 N/m.
    EXPECT_FALSE(inspector.edit("stiffness", 1e9));
    EXPECT_NE(inspector.warning().indexOf("stab"), -1) << inspector.warning().toStdString();
    EXPECT_EQ(text_of(document.model()), before) << "nothing changed";
    EXPECT_FALSE(inspector.edit("stiffness", -5));
    // Its own margin is on show: how far the stiffness may go before the scheme is unstable.
    bool margin_shown = false;
    for (QLabel* label : inspector.findChildren<QLabel*>())
        margin_shown = margin_shown || label->text().startsWith("below ");
    EXPECT_TRUE(margin_shown);
    EXPECT_EQ(text_of(document.model()), before);
    document.undo_stack().undo();
    EXPECT_EQ(document.model().find_lia("k2")->stiffness, 100) << "the applied edit undoes";
}

// A finger shows as a fingertip over the point it stops, between two masses; the inspector
// moves it along the string and refuses a place off it.
TEST(FingerInTheEditor, ItsFingertipSitsWhereItStopsAndTheInspectorMovesIt) {
    BowedStringOptions o;
    o.pitch = 440, o.finger = true, o.finger_position = 2.0 / 3.0, o.with_gesture = false;
    ModelDocument document;
    document.reset(build_bowed_string(o));
    GraphView view(document);
    view.resize(1000, 300);
    view.show();
    view.fit();
    auto between = [&](double position) {
        const Lia& finger = *document.model().find_lia("finger");
        const double u = position * static_cast<double>(finger.along.size() - 1);
        const auto first = static_cast<std::size_t>(u);
        const QPointF a = view.node_position(QString::fromStdString(finger.along[first]));
        const QPointF b = view.node_position(QString::fromStdString(finger.along[first + 1]));
        return a.x() + (u - static_cast<double>(first)) * (b.x() - a.x());
    };
    EXPECT_NEAR(view.node_position("finger").x(), between(2.0 / 3.0), 1e-6);
    Inspector inspector(document);
    inspector.show_element("finger");
    EXPECT_TRUE(inspector.edit("position", 0.5)) << inspector.warning().toStdString();
    EXPECT_EQ(document.model().find_lia("finger")->finger_position, 0.5);
    EXPECT_NEAR(view.node_position("finger").x(), between(0.5), 1e-6) << "it moved";
    QDir().mkpath(ARCHET_ARTIFACT_DIR);
    view.grab().save(QDir(ARCHET_ARTIFACT_DIR).filePath("graph-finger.png"));
    EXPECT_TRUE(inspector.edit("pressure", 0.03)) << "a light touch";
    EXPECT_FALSE(inspector.edit("position", 1.5));
    EXPECT_NE(inspector.warning().indexOf("at most 1"), -1) << inspector.warning().toStdString();
    EXPECT_EQ(document.model().find_lia("finger")->finger_position, 0.5) << "refused: unchanged";
}

// The pad's keyboard row is the pad's while it has the keyboard: F plays the fourth there (it is
// Freeze elsewhere), and a key let go after the pad lost the keyboard does not leave the finger
// down.
TEST(GesturePadKeys, FIsTheFourthOnThePadAndLosingTheKeyboardLiftsTheFinger) {
    MainWindow window(test::editor_alone());
    window.show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
    window.activateWindow();
    window.pad().setFocus();
    QSignalSpy notes(&window.pad(), &GesturePad::note);
    QTest::keyPress(&window.pad(), Qt::Key_F);
    ASSERT_EQ(notes.count(), 1) << "F reached the pad";
    EXPECT_EQ(notes[0][0].toInt(), 5);
    window.graph().setFocus();
    QTest::qWait(20);
    ASSERT_EQ(notes.count(), 2);
    EXPECT_EQ(notes[1][0].toInt(), -1) << "back to the open string";
}

TEST(CompareViewTest, RendersTwoDampingsSideBySide) {
    CompareView view(load_model_file(test::resource("models/bowed-string-220-paper.json")));
    view.resize(1200, 800);
    view.show();
    view.set_variation("string.damping", "0.0005, 0.005");
    bool done = false;
    QObject::connect(&view, &CompareView::rendered, [&] { done = true; });
    view.render();
    ASSERT_TRUE(test::wait_until([&] { return done; }, 300000))
        << "rendered off the GUI thread (waited for, however slow the machine)";
    ASSERT_EQ(view.runs().size(), 2u);
    EXPECT_EQ(view.figure().columns(), 2);
    EXPECT_GT(view.runs()[1].dissipated_per_period, view.runs()[0].dissipated_per_period);
    QDir().mkpath(ARCHET_ARTIFACT_DIR);
    EXPECT_TRUE(view.grab().save(QDir(ARCHET_ARTIFACT_DIR).filePath("studio-compare.png")));
    // A/B: the first variant plays (on a device, or a null sink clocked in real time).
    view.player().play(view.runs()[0].audio, view.runs()[0].sample_rate);
    EXPECT_TRUE(test::wait_until([&] { return view.player().position() > 1000u; }, 60000))
        << view.player().description();
    view.player().stop();
}

TEST(CompareViewTest, ABadVariationIsSaidAndNothingRuns) {
    CompareView view(load_model_file(test::resource("models/bowed-string-220.json")));
    view.set_variation("bow.position", "0.1, 0.9");
    view.render();
    EXPECT_FALSE(view.busy());
    EXPECT_TRUE(view.runs().empty());
}

TEST(NewStringDialogTest, ItsDefaultsBuildTheShippedString) {
    NewStringDialog dialog;
    const Model built = build_bowed_string(dialog.options());
    EXPECT_EQ(format_model(built),
              format_model(load_model_file(test::resource("models/bowed-string-220.json"))))
        << "the dialog's defaults are the builder's (and the shipped 220 Hz string's)";
}

// A cello's C string: its material in the dialog, and the length it gives at the pitch.
TEST(NewStringDialogTest, TakesTheStringsMaterialAndShowsItsLength) {
    NewStringDialog dialog;
    auto* length = dialog.findChild<QLabel*>("string_length");
    ASSERT_NE(length, nullptr);
    EXPECT_EQ(length->text(), "0.64 m");  // a violin A string tuned down to 220 Hz
    dialog.findChild<QDoubleSpinBox*>("pitch")->setValue(65.4);
    EXPECT_EQ(length->text(), "2.15 m") << "the violin A string's material at a cello's C";
    dialog.findChild<QDoubleSpinBox*>("tension")->setValue(130);
    dialog.findChild<QDoubleSpinBox*>("density")->setValue(0.0148);
    EXPECT_EQ(length->text(), "0.72 m");
    const BowedStringOptions o = dialog.options();
    EXPECT_EQ(o.tension, 130.0);
    EXPECT_EQ(o.linear_density, 0.0148);
    EXPECT_EQ(o.pitch, 65.4);
    QDir().mkpath(ARCHET_ARTIFACT_DIR);
    EXPECT_TRUE(dialog.grab().save(QDir(ARCHET_ARTIFACT_DIR).filePath("new-string-dialog.png")));
}

TEST(PlayabilityPanelTest, ComputesInTheBackgroundMarksTheGestureAndPlaysAClickedPoint) {
    const Model model = load_model_file(test::resource("models/bowed-string-220.json"));
    PlayabilityPanel panel(model, [] { return std::make_pair(0.115, 0.15); });
    panel.resize(1000, 800);
    panel.show();
    MapGrid grid;
    grid.force_min = 0.005, grid.force_max = 1.5, grid.force_steps = 5;
    grid.position_min = 0.08, grid.position_max = 0.2, grid.position_steps = 3;
    grid.duration = 0.6;
    panel.set_grid(grid);
    QString error = "not yet";
    QObject::connect(&panel, &PlayabilityPanel::computed, [&](const QString& e) { error = e; });
    panel.compute();
    EXPECT_TRUE(panel.busy());
    ASSERT_TRUE(test::wait_until([&] { return error != "not yet"; }, 300000));
    ASSERT_TRUE(error.isEmpty()) << error.toStdString();
    ASSERT_EQ(panel.points().size(), 15u);
    QTest::qWait(300);  // the gesture's cross is drawn by the refresh timer
    QDir().mkpath(ARCHET_ARTIFACT_DIR);
    EXPECT_TRUE(panel.grab().save(QDir(ARCHET_ARTIFACT_DIR).filePath("studio-playability.png")));
    // A click on a point plays it.
    auto& plot = panel.figure().plot();
    const MapPoint& p = panel.points()[7];
    const QPoint pixel(static_cast<int>(plot.xAxis->coordToPixel(p.position)),
                       static_cast<int>(plot.yAxis->coordToPixel(p.force)));
    EXPECT_EQ(panel.figure().point_at(pixel), 7);
    panel.listen(7);
    EXPECT_TRUE(test::wait_until([&] { return panel.player().position() > 1000u; }, 60000));
    panel.player().stop();
    // What it says of the point is what the map found there.
    const QString heard = QString("(%1 slips per period, %2 cents)")
                              .arg(p.analysis.slips_per_period, 0, 'f', 2)
                              .arg(p.analysis.pitch_cents, 0, 'f', 1);
    bool told = false;
    for (const QLabel* label : panel.findChildren<QLabel*>())
        told = told || label->text().contains(heard);
    EXPECT_TRUE(told) << heard.toStdString();
    // Where the string plays in Helmholtz motion, the message says how flat it plays against
    // the string's first mode.
    MapGrid helmholtz;
    helmholtz.force_min = 0.02, helmholtz.force_max = 0.067, helmholtz.force_steps = 3;
    helmholtz.position_min = helmholtz.position_max = 0.12, helmholtz.position_steps = 1;
    helmholtz.speed = 0.05, helmholtz.duration = 1.5;
    panel.set_grid(helmholtz);
    error = "not yet";
    panel.compute();
    ASSERT_TRUE(test::wait_until([&] { return error != "not yet"; }, 300000));
    bool said = false;
    for (const QLabel* label : panel.findChildren<QLabel*>())
        said = said || (label->text().startsWith("3 of 3 points in Helmholtz motion, playing -") &&
                        label->text().contains("cents against the string's first mode"));
    EXPECT_TRUE(said);
}

TEST(ModesPanelTest, FindsTheStringsFundamental) {
    ModelDocument document;
    ModesPanel panel(document);
    document.reset(load_model_file(test::resource("models/bowed-string-220-harmonic.json")));
    ASSERT_TRUE(test::wait_until([&] { return !panel.computing(); }, 30000));
    EXPECT_NEAR(panel.fundamental(), 220.0, 1e-6);
    EXPECT_GT(panel.mode_count(), 20);
}

// Every mode is listed, up to the string's highest (a 214-mass string has more than 200), in
// columns wide enough for what they show: a frequency of 1 kHz and more is not cut short.
TEST(ModesPanelTest, ListsEveryModeInColumnsWideEnoughForThem) {
    ModelDocument document;
    ModesPanel panel(document);
    const Model model = load_model_file(test::resource("models/bowed-string-110.json"));
    document.reset(model);
    ASSERT_TRUE(test::wait_until([&] { return !panel.computing(); }, 30000));
    EXPECT_EQ(panel.mode_count(), static_cast<int>(analyse_modes(model).modes.size()));
    EXPECT_GT(panel.mode_count(), 200);
    panel.resize(320, 600);  // as narrow as the studio's side panel gets
    panel.show();
    const QTableWidget* table = panel.findChild<QTableWidget*>();
    ASSERT_NE(table, nullptr);
    for (int column = 0; column < table->columnCount(); ++column) {
        const QString header = table->horizontalHeaderItem(column)->text();
        int widest = table->horizontalHeader()->fontMetrics().horizontalAdvance(header);
        for (int row = 0; row < table->rowCount(); ++row)
            widest = std::max(
                widest, table->fontMetrics().horizontalAdvance(table->item(row, column)->text()));
        EXPECT_GT(table->horizontalHeader()->sectionSize(column), widest)
            << "column " << header.toStdString();
    }
}

// The cents chart has room for its axis label, in a panel as small as the studio's side panel
// gets on a 1000-pixel screen (about 400 by 420).
TEST(ModesPanelTest, TheCentsChartHasRoomForItsAxisLabel) {
    ModelDocument document;
    ModesPanel panel(document);
    document.reset(load_model_file(test::resource("models/bowed-string-110.json")));
    ASSERT_TRUE(test::wait_until([&] { return !panel.computing(); }, 30000));
    panel.resize(400, 420);
    panel.show();
    QCustomPlot* chart = panel.findChild<QCustomPlot*>();
    ASSERT_NE(chart, nullptr);
    chart->replot();
    const int label =
        QFontMetrics(chart->yAxis->labelFont()).horizontalAdvance(chart->yAxis->label());
    EXPECT_GE(chart->axisRect()->height(), label) << chart->yAxis->label().toStdString();
}

// An edit of the bow leaves the string as it was: its modes are shown again without another
// eigenvalue solve. An edit of the string solves it again.
TEST(ModesPanelTest, SolvesAgainOnlyWhenAnEditChangesTheString) {
    ModelDocument document;
    ModesPanel panel(document);
    document.reset(load_model_file(test::resource("models/bowed-string-220.json")));
    ASSERT_TRUE(test::wait_until([&] { return !panel.computing(); }, 30000));
    ASSERT_EQ(panel.solves_made(), 1u);
    const double f1 = panel.fundamental();
    const int modes = panel.mode_count();
    document.edit_parameter(ParameterName::parse("friction.mu_s"), 0.7);
    EXPECT_TRUE(panel.computing()) << "the edit asks for the modes again";
    ASSERT_TRUE(test::wait_until([&] { return !panel.computing(); }, 30000));
    EXPECT_EQ(panel.solves_made(), 1u);
    EXPECT_EQ(panel.fundamental(), f1);
    EXPECT_EQ(panel.mode_count(), modes);
    document.edit_parameter(ParameterName::parse("k5.damping"), 0.004);
    EXPECT_TRUE(panel.computing());
    ASSERT_TRUE(test::wait_until([&] { return !panel.computing(); }, 30000));
    EXPECT_EQ(panel.solves_made(), 2u);
    EXPECT_NEAR(panel.fundamental(), 220.0, 1.0);
}

TEST(ModesPanelTest, ShowsHertzToOneDecimalAndACentsChartScaledToTheData) {
    ModelDocument document;
    ModesPanel panel(document);
    panel.resize(500, 700);
    panel.show();
    auto* table = panel.findChild<QTableWidget*>();
    auto* chart = panel.findChild<QCustomPlot*>();
    ASSERT_NE(table, nullptr);
    ASSERT_NE(chart, nullptr);
    const QRegularExpression hertz(R"(^\d+(\.\d)? Hz$)");
    for (const char* shipped :
         {"models/bowed-string-220.json", "models/bowed-string-220-harmonic.json"}) {
        document.reset(load_model_file(test::resource(shipped)));
        ASSERT_TRUE(test::wait_until([&] { return !panel.computing(); }, 30000));
        ASSERT_GT(table->rowCount(), 10) << shipped;
        double lowest = 0, highest = 0;
        bool fundamental_seen = false;
        for (int row = 0; row < table->rowCount(); ++row) {
            const QString frequency = table->item(row, 1)->text();
            EXPECT_TRUE(hertz.match(frequency).hasMatch()) << frequency.toStdString();
            fundamental_seen = fundamental_seen || frequency == "220.0 Hz";
            bool number = false;
            const double cents = table->item(row, 3)->text().toDouble(&number);
            if (number) lowest = std::min(lowest, cents), highest = std::max(highest, cents);
        }
        EXPECT_TRUE(fundamental_seen) << shipped;
        const QCPRange range = chart->yAxis->range();
        // Every bar in view (to the 0.05 cents the table rounds to), 0 included ...
        EXPECT_LE(range.lower, lowest + 0.05) << shipped;
        EXPECT_GE(range.upper, highest - 0.05) << shipped;
        // ... at least the ±5 cents below which the ear hears nothing, and not much more than
        // the data need.
        EXPECT_GE(range.size(), ModesPanel::kCentsSpan - 1e-9) << shipped;
        EXPECT_LE(range.size(), std::max(ModesPanel::kCentsSpan, 1.5 * (highest - lowest)) + 0.1)
            << shipped;
        chart->replot();
        const QVector<QString> labels = chart->yAxis->tickVectorLabels();
        EXPECT_EQ(std::set<QString>(labels.begin(), labels.end()).size(),
                  static_cast<std::size_t>(labels.size()))
            << shipped;
    }
}

TEST(PlayabilityFigureTest, TheLegendNamesEachRegimeInWords) {
    const Model model = load_model_file(test::resource("models/bowed-string-220.json"));
    MapGrid grid;
    grid.force_steps = 1, grid.position_steps = 5;
    std::vector<MapPoint> points;
    for (Regime r : {Regime::Helmholtz, Regime::MultipleSlip, Regime::Raucous, Regime::AnomalousLow,
                     Regime::Silent}) {
        MapPoint p;
        p.index = points.size();
        p.force = grid.force(p.index), p.position = grid.position(p.index);
        p.analysis.regime = r;
        points.push_back(p);
    }
    PlayabilityFigure figure;
    figure.resize(1000, 700);
    figure.show_map(grid, points, schelleng_lines(model));
    std::set<QString> names;
    QCPLegend& legend = *figure.plot().legend;
    for (int i = 0; i < legend.itemCount(); ++i)
        if (auto* item = qobject_cast<QCPPlottableLegendItem*>(legend.item(i)))
            names.insert(item->plottable()->name());
    for (const char* words : {"Helmholtz", "multiple slip", "raucous", "anomalous low", "silent"})
        EXPECT_EQ(names.count(words), 1u) << words;
    for (const QString& name : names)
        EXPECT_FALSE(name.contains('_') || name == "helmholtz") << name.toStdString();
}

// A probe history of the streams the scopes read: the bowing point barely moves (round-off
// on a constant), the output is `sound(t)`.
ProbeHistory history_of(std::size_t samples, double rate, double (*sound)(double)) {
    ProbeHistory history;
    history.reset({"bow_point_x", "friction_force", "bow_point_v", "bow_v", "slip_v"});
    for (std::size_t i = 0; i < samples; ++i) {
        const double noise = 1e-12 * std::sin(1.7 * static_cast<double>(i));
        ipc::ProbeFrame frame{};
        frame.tick = i;
        frame.count = 5;
        frame.values[0] = (0.0568245 + noise) * 1e-3;  // m: 0.0568245 mm
        frame.values[1] = 0.0568245 + noise;           // N
        frame.values[2] = frame.values[3] = noise;     // m/s
        frame.values[4] = 0;
        frame.output = sound(static_cast<double>(i) / rate);
        history.append(frame);
    }
    return history;
}

double two_partials(double t) {
    return std::sin(2 * std::numbers::pi * 110 * t) +
           0.5 * std::sin(2 * std::numbers::pi * 220 * t);
}

TEST(ScopePanelTest, ANearlyConstantSignalKeepsEveryAxisReadable) {
    ScopePanel panel;
    panel.resize(1200, 800);
    panel.show();
    panel.set_trigger_on_slip(false);
    const ProbeHistory history = history_of(4000, 48000, two_partials);
    std::vector<float> shape(62, 1e-9f);
    std::vector<double> along(62);
    for (std::size_t i = 0; i < along.size(); ++i) along[i] = static_cast<double>(i);
    panel.refresh(history, shape, along, 48000);
    using Scope = ScopePanel::Scope;
    const struct {
        const char* name;
        QCPAxis* axis;
        double minimum_span, centre;
    } axes[] = {
        {"displacement", panel.plot(Scope::Displacement).yAxis, ScopePanel::kDisplacementSpanMm,
         0.0568245},
        {"force", panel.plot(Scope::Force).yAxis, ScopePanel::kForceSpanN, 0.0568245},
        {"velocity", panel.plot(Scope::Velocity).yAxis, ScopePanel::kVelocitySpanMPerS, 0},
        {"Fig. 5 displacement", panel.plot(Scope::ForceAgainstDisplacement).xAxis,
         ScopePanel::kDisplacementSpanMm, 0.0568245},
        {"Fig. 5 force", panel.plot(Scope::ForceAgainstDisplacement).yAxis, ScopePanel::kForceSpanN,
         0.0568245},
        {"string", panel.plot(Scope::Shape).yAxis, ScopePanel::kShapeSpanMm, 0},
    };
    for (const auto& a : axes) {
        a.axis->parentPlot()->replot();
        EXPECT_GE(a.axis->range().size(), a.minimum_span * (1 - 1e-9)) << a.name;
        EXPECT_NEAR(a.axis->range().center(), a.centre, 1e-6) << a.name << ": centred on the data";
        const QVector<QString> labels = a.axis->tickVectorLabels();
        EXPECT_GE(labels.size(), 3) << a.name;
        EXPECT_EQ(std::set<QString>(labels.begin(), labels.end()).size(),
                  static_cast<std::size_t>(labels.size()))
            << a.name << ": " << QStringList(labels.begin(), labels.end()).join(" ").toStdString();
    }
    QCoreApplication::processEvents();  // the queued replots
    QDir().mkpath(ARCHET_ARTIFACT_DIR);
    EXPECT_TRUE(panel.grab().save(QDir(ARCHET_ARTIFACT_DIR).filePath("studio-scopes-still.png")));
}

// The local maxima of the drawn spectrum within 20 dB of its highest: the partials.
std::vector<double> spectrum_peaks(QCustomPlot& plot) {
    const auto data = plot.graph(0)->data();
    double highest = -1e300;
    for (const auto& point : *data) highest = std::max(highest, point.value);
    std::vector<double> peaks;
    for (auto it = data->constBegin() + 1; it + 1 < data->constEnd(); ++it)
        if (it->value > highest - 20 && it->value > (it - 1)->value && it->value >= (it + 1)->value)
            peaks.push_back(it->key);
    return peaks;
}

TEST(ScopePanelTest, TheSpectrumResolvesTheLowestStringsPartialsAndSaysItsResolution) {
    for (const double rate : {48000.0, 44100.0}) {
        ScopePanel panel;
        panel.resize(1200, 800);
        panel.show();
        const std::size_t window = ScopePanel::spectrum_window(rate);
        const double resolution = rate / static_cast<double>(window);
        EXPECT_LE(resolution, 12) << "partials 110 Hz apart stay apart under a Hann window";
        QCustomPlot& spectrum = panel.plot(ScopePanel::Scope::Spectrum);

        panel.refresh(history_of(window / 2, rate, two_partials), {}, {}, rate);
        EXPECT_TRUE(spectrum.graph(0)->data()->isEmpty()) << "no spectrum from half a window";
        EXPECT_NE(spectrum.xAxis->label().indexOf("waiting"), -1)
            << spectrum.xAxis->label().toStdString();

        panel.refresh(history_of(window + 100, rate, two_partials), {}, {}, rate);
        const QString said = QString("resolution %1 Hz").arg(resolution, 0, 'f', 1);
        EXPECT_NE(spectrum.xAxis->label().indexOf(said), -1)
            << spectrum.xAxis->label().toStdString() << " should say " << said.toStdString();
        const std::vector<double> peaks = spectrum_peaks(spectrum);
        ASSERT_EQ(peaks.size(), 2u) << rate;
        EXPECT_NEAR(peaks[0], 110, resolution) << rate;
        EXPECT_NEAR(peaks[1], 220, resolution) << rate;
    }
}

// The spectrum's axis says its resolution, or how much sound it waits for, in lines that fit
// under the plot as the studio's window lays it out (the scopes share its middle), with room for
// a font half as large again as this one (Qt's VNC platform draws one so).
TEST(ScopePanelTest, TheSpectrumsAxisLabelFitsUnderItInTheStudio) {
    MainWindow window(test::editor_alone());
    window.show();
    auto* panel = window.findChild<ScopePanel*>();
    ASSERT_NE(panel, nullptr);
    QCustomPlot& spectrum = panel->plot(ScopePanel::Scope::Spectrum);
    const std::size_t samples = ScopePanel::spectrum_window(48000);
    for (const std::size_t heard : {samples / 2, samples + 100}) {
        panel->refresh(history_of(heard, 48000, two_partials), {}, {}, 48000);
        spectrum.replot();
        const QString label = spectrum.xAxis->label();
        const QFontMetrics metrics(spectrum.xAxis->labelFont());
        for (const QString& line : label.split('\n'))
            EXPECT_LE(1.5 * metrics.horizontalAdvance(line), spectrum.width())
                << line.toStdString() << " (" << heard << " samples heard)";
    }
}

}  // namespace
}  // namespace archet::ui
