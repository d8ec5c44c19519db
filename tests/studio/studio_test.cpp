// The studio under Qt's offscreen platform, with a real engine process: it opens the shipped
// string and plays it, the pad bows it, the scopes fill with the string's motion, and a killed
// engine is noticed and restarted with the same model. Screenshots of the window while bowing
// are written to build/test-artifacts/ (look at them).

#include <gtest/gtest.h>
#include <signal.h>

#include <fstream>

#include <qcustomplot.h>
#include <QApplication>
#include <QDir>
#include <QFileInfo>
#include <QListWidget>
#include <QMouseEvent>
#include <QStandardPaths>
#include <QStatusBar>
#include <QTest>
#include <QWheelEvent>

#include "archet/files/model_file.hpp"
#include "archet/ipc/segment_layout.hpp"
#include "archet/model/string_points.hpp"
#include "archet/sound_examples.hpp"
#include "archet/ui/elided_label.hpp"
#include "archet/ui/gesture_pad.hpp"
#include "archet/ui/graph_view.hpp"
#include "archet/ui/inspector.hpp"
#include "archet/ui/library_panel.hpp"
#include "archet/ui/main_window.hpp"
#include "archet/ui/model_document.hpp"
#include "archet/ui/scope_panel.hpp"
#include "archet/ui/sound_examples_dialog.hpp"
#include "archet/ui/takes_panel.hpp"
#include "archet/ui/widget_export.hpp"
#include "deadline_witness.hpp"
#include "studio_test_support.hpp"
#include "test_support.hpp"

namespace archet::ui {
namespace {

EngineClientOptions engine_options() {
    EngineClientOptions o;
    o.archet_binary = ARCHET_BINARY;
    o.audio = "null";  // clocked in real time, like a sound card
    return o;
}

void save_screenshot(QWidget& widget, const QString& name) {
    QDir().mkpath(ARCHET_ARTIFACT_DIR);
    const QString path = QDir(ARCHET_ARTIFACT_DIR).filePath(name);
    EXPECT_TRUE(widget.grab().save(path)) << path.toStdString();
}

// Bows with the pad for `seconds` of sound: pressed in, moving across at 0.1 m/s. Time is the
// sound's, counted in the samples the studio received, not wall-clock time, which a slow
// machine (TSan) stretches (a generous minute at most).
void bow(MainWindow& window, double seconds, double start_slide = -0.1) {
    const std::uint64_t from = window.engine().history().frames_received();
    const std::uint64_t until = from + static_cast<std::uint64_t>(seconds * 48000);
    QElapsedTimer clock;
    clock.start();
    while (window.engine().history().frames_received() < until &&
           clock.elapsed() < 60000 + seconds * 1000) {
        const double t =
            static_cast<double>(window.engine().history().frames_received() - from) / 48000;
        window.pad().set_position(start_slide + 0.1 * t, std::min(0.0015, 0.05 * t));
        QTest::qWait(10);
    }
}

using test::wait_until;

TEST(Studio, PlaysTheShippedStringAndTheScopesFollowTheBow) {
    const EngineClientOptions options = engine_options();
    test::DeadlineWitness machine(
        std::chrono::nanoseconds(1'000'000'000LL * options.buffer_frames / 48000));
    MainWindow window(options);
    ASSERT_TRUE(window.open_file(test::resource("models/bowed-string-220.json").c_str()));
    window.show();
    ASSERT_TRUE(wait_until([&] { return window.engine().status().state == "running"; }, 60000));
    ASSERT_TRUE(
        wait_until([&] { return window.engine().status().model == "bowed-string-220"; }, 60000));
    bow(window, 1.5);
    const ProbeHistory& h = window.engine().history();
    EXPECT_GT(h.frames_received(), 40000u) << "the probe stream runs at the audio rate";
    EXPECT_GT(std::abs(h.latest(h.channel("friction_force"))), 1e-3) << "the pad bows the string";
    EXPECT_GT(window.scopes().drawn_samples(), 900) << "20 ms of the string at 48 kHz";
    EXPECT_EQ(window.engine().shape().size(),
              string_points(load_model_file(test::resource("models/bowed-string-220.json"))).size())
        << "the string's bridge, masses and nut";
    EXPECT_EQ(window.engine().status().realtime_allocations, 0u);
    save_screenshot(window, "studio-bowing.png");
    machine.stop();
    // As in audio_test: on a machine that stalls, no more xruns than its own stalls.
    const auto xruns = window.engine().status().xruns;
    if (machine.missed() > 0) {
        EXPECT_LE(xruns, machine.missed()) << machine.describe();
        if (xruns > 0)
            GTEST_SKIP() << xruns << " xruns: zero cannot be asked here; " << machine.describe();
    }
    EXPECT_EQ(xruns, 0u) << machine.describe();
}

// A string longer than the engine's shape frame holds (a plucked chain of 600 masses, 602
// points with its ends) reaches the string scope from end to end, each of the 512 points it is
// drawn from at its place along the string.
TEST(Studio, DrawsAStringLongerThanAShapeFrameFromEndToEnd) {
    const auto dir = test::temp_dir("studio-long-shape");
    const Model plucked = test::plucked_chain(600);
    write_file_atomically(dir / "plucked.json", format_model(plucked));
    MainWindow window(engine_options());
    ASSERT_TRUE(window.open_file((dir / "plucked.json").c_str()));
    window.show();
    ASSERT_TRUE(wait_until(
        [&] { return window.engine().status().model == QString::fromStdString(plucked.name); },
        60000));
    ASSERT_TRUE(
        wait_until([&] { return window.engine().shape().size() == ipc::kMaxShapePoints; }, 60000));
    const std::vector<double>& along = window.engine().shape_along();
    ASSERT_EQ(along.size(), ipc::kMaxShapePoints);
    EXPECT_EQ(along.front(), 0.0);
    EXPECT_EQ(along.back(), 601.0) << "the far end";
    QCustomPlot& plot = window.scopes().plot(ScopePanel::Scope::Shape);
    ASSERT_TRUE(wait_until([&] { return plot.graph(0)->data()->size() > 0; }, 60000));
    EXPECT_EQ(plot.graph(0)->data()->size(), static_cast<int>(ipc::kMaxShapePoints));
    EXPECT_EQ(plot.graph(0)->data()->at(plot.graph(0)->data()->size() - 1)->key, 601.0);
    EXPECT_GE(plot.xAxis->range().upper, 601.0);
}

TEST(Studio, AKilledEngineIsRestartedWithTheSameModel) {
    MainWindow window(engine_options());
    ASSERT_TRUE(window.open_file(test::resource("models/bowed-string-440.json").c_str()));
    window.show();
    ASSERT_TRUE(
        wait_until([&] { return window.engine().status().model == "bowed-string-440"; }, 60000));
    bow(window, 0.3);
    const pid_t first = window.engine().engine_pid();
    ::kill(first, SIGKILL);
    ASSERT_TRUE(wait_until([&] { return window.engine().status().restarts == 1; }, 60000))
        << "the studio noticed";
    EXPECT_NE(window.engine().engine_pid(), first);
    auto* status = window.findChild<ElidedLabel*>();
    ASSERT_NE(status, nullptr);
    EXPECT_TRUE(status->full_text().contains("The engine was restarted once: the engine exited"))
        << status->full_text().toStdString();
    EXPECT_EQ(status->toolTip(), status->full_text()) << "the whole text, however long";
    ASSERT_TRUE(wait_until(
        [&] {
            return window.engine().status().state == "running" &&
                   window.engine().status().model == "bowed-string-440";
        },
        60000))
        << "and the new engine plays the same model";
    const auto before = window.engine().history().frames_received();
    bow(window, 0.5, 0.0);
    EXPECT_GT(window.engine().history().frames_received(), before + 10000) << "playing again";
    save_screenshot(window, "studio-after-restart.png");
}

TEST(Studio, EditsReachTheRunningEngine) {
    MainWindow window(engine_options());
    ASSERT_TRUE(window.open_file(test::resource("models/bowed-string-220.json").c_str()));
    ASSERT_TRUE(
        wait_until([&] { return window.engine().status().model == "bowed-string-220"; }, 60000));
    QStringList messages;
    int loads = 0;
    QObject::connect(&window.engine(), &EngineClient::message,
                     [&](const QString& text) { messages << text; });
    QObject::connect(&window.engine(), &EngineClient::model_loaded, [&] { ++loads; });
    // A parameter glides into the running model: no reload, no complaint.
    window.graph().select({"friction"});
    ASSERT_EQ(window.inspector().element(), "friction");
    ASSERT_TRUE(window.inspector().edit("mu_s", 0.7));
    window.show();
    bow(window, 0.3);
    save_screenshot(window, "studio-inspector.png");
    EXPECT_EQ(loads, 0);
    EXPECT_TRUE(messages.isEmpty()) << messages.join("; ").toStdString();
    // A new element reloads it.
    window.document().add_mat(MatKind::Oscillator, {0, 200});
    ASSERT_TRUE(wait_until([&] { return loads == 1; }, 60000)) << messages.join("; ").toStdString();
    // And undo brings the shipped model back to the engine.
    window.document().undo_stack().undo();
    ASSERT_TRUE(wait_until([&] { return loads == 2; }, 60000));
    window.document().undo_stack().undo();
    EXPECT_EQ(format_model(window.document().model()),
              format_model(load_model_file(test::resource("models/bowed-string-220.json"))));
}

TEST(Studio, RecordsATakeAndPlaysAndExportsIt) {
    const auto dir = test::temp_dir("studio-takes");
    MainWindow window(engine_options());
    window.set_takes_folder(QString::fromStdString((dir / "takes").string()));
    ASSERT_TRUE(window.open_file(test::resource("models/bowed-string-220.json").c_str()));
    window.show();
    window.activateWindow();
    ASSERT_TRUE(QTest::qWaitForWindowActive(&window)) << "keyboard shortcuts need it";
    ASSERT_TRUE(
        wait_until([&] { return window.engine().status().model == "bowed-string-220"; }, 60000));
    bow(window, 0.3);
    QTest::keyClick(&window, Qt::Key_R);  // record
    bow(window, 1.0, -0.07);
    QTest::keyClick(&window, Qt::Key_R);  // stop
    ASSERT_TRUE(wait_until([&] { return window.takes().takes().size() == 1; }, 60000))
        << "the written take is listed";
    window.takes().select(window.takes().takes().front());
    ASSERT_TRUE(window.takes().play());
    EXPECT_TRUE(wait_until([&] { return window.takes().player().position() > 2000u; }, 60000))
        << "it plays back";
    window.takes().player().stop();
    const QString flac = QString::fromStdString((dir / "take.flac").string());
    ASSERT_TRUE(window.takes().export_to(flac));
    EXPECT_GT(QFileInfo(flac).size(), 10000);
    const QString csv = QString::fromStdString((dir / "take.csv").string());
    ASSERT_TRUE(window.takes().export_to(csv));
    EXPECT_GT(QFileInfo(csv).size(), 100000) << "a probe row per sample";
    // The scopes as images, for a paper.
    for (const char* name : {"scopes.png", "scopes.pdf"}) {
        const QString path = QString::fromStdString((dir / name).string());
        EXPECT_TRUE(save_widget_image(window.scopes(), path)) << name;
        EXPECT_GT(QFileInfo(path).size(), 5000) << name;
    }
}

// A take that clips says so where the player sees it, in the Takes tab and the status bar,
// though the live limiter kept what was heard clean.
TEST(Studio, ATakeThatClippedSaysSo) {
    const auto dir = test::temp_dir("studio-take-clip");
    auto text = test::read_file(test::resource("models/bowed-string-220.json"));
    const auto at = text.find("\"output_gain\": ");
    text.replace(at, text.find(',', at) - at, "\"output_gain\": 500.0");
    { std::ofstream(dir / "loud.json") << text; }
    MainWindow window(engine_options());
    window.set_takes_folder(QString::fromStdString((dir / "takes").string()));
    ASSERT_TRUE(window.open_file(QString::fromStdString((dir / "loud.json").string())));
    window.show();
    window.activateWindow();
    ASSERT_TRUE(QTest::qWaitForWindowActive(&window)) << "keyboard shortcuts need it";
    ASSERT_TRUE(
        wait_until([&] { return window.engine().status().model == "bowed-string-220"; }, 5000));
    QTest::keyClick(&window, Qt::Key_R);  // record
    bow(window, 0.8, -0.07);
    QTest::keyClick(&window, Qt::Key_R);  // stop
    ASSERT_TRUE(wait_until([&] { return window.takes().note().startsWith("take written"); }, 10000))
        << window.takes().note().toStdString();
    EXPECT_TRUE(window.takes().note().contains("clipped at full scale"))
        << window.takes().note().toStdString();
    EXPECT_TRUE(window.takes().note().contains("output_gain"));
    EXPECT_TRUE(window.statusBar()->currentMessage().contains("clipped"))
        << window.statusBar()->currentMessage().toStdString();
}

TEST(Studio, NewSettingsRestartTheEngineWithTheSameModel) {
    MainWindow window(engine_options());
    ASSERT_TRUE(window.open_file(test::resource("models/bowed-string-440.json").c_str()));
    ASSERT_TRUE(
        wait_until([&] { return window.engine().status().model == "bowed-string-440"; }, 60000));
    EngineClientOptions o = window.engine().options();
    o.buffer_frames = 256;
    o.haptic = "none";
    window.engine().reconfigure(o);
    ASSERT_TRUE(wait_until(
        [&] {
            return window.engine().status().model == "bowed-string-440" &&
                   window.engine().status().device.contains("256 frames");
        },
        60000))
        << window.engine().status().device.toStdString();
}

TEST(Studio, AutosaveKeepsTheEditsAndTheLibraryOffersThem) {
    const auto dir = test::temp_dir("studio-autosave");
    MainWindow window(engine_options());
    window.set_autosave_folder(QString::fromStdString(dir.string()));
    ASSERT_TRUE(window.open_file(test::resource("models/bowed-string-880.json").c_str()));
    window.document().edit_parameter({"friction", "mu_s"}, 0.75);
    const QString saved = window.autosave();
    EXPECT_EQ(format_model(load_model_file(saved.toStdString())),
              format_model(window.document().model()));
    window.set_resources_folder(QString::fromStdString(test::resource("").string()));
    bool offered = false;
    for (QListWidget* list : window.library().findChildren<QListWidget*>())
        for (int i = 0; i < list->count(); ++i)
            offered = offered || list->item(i)->text().contains("autosaved");
    EXPECT_TRUE(offered);
}

TEST(Studio, WithoutAnEngineBinaryItSaysSoAndStaysUp) {
    EngineClientOptions o = engine_options();
    o.archet_binary = "/nonexistent/archet";
    MainWindow window(o);
    ASSERT_TRUE(window.open_file(test::resource("models/bowed-string-220.json").c_str()));
    EXPECT_EQ(window.engine().status().state, "not running");
    window.document().edit_parameter({"friction", "mu_s"}, 0.7);  // editing still works
    EXPECT_EQ(window.document().model().find_lia("friction")->mu_static, 0.7);
}

// Every line the inspector shows of a string mass reads whole in the studio's side panel, at
// the window's own size: a long one (the stability margin) wraps rather than widening the
// inspector past the edge of its tab.
TEST(Studio, TheInspectorOfAStringMassReadsWholeInItsTab) {
    EngineClientOptions o = engine_options();
    o.archet_binary = "/nonexistent/archet";  // the inspector needs no engine
    MainWindow window(o);
    ASSERT_TRUE(window.open_file(test::resource("models/bowed-string-110.json").c_str()));
    window.show();
    auto* inspector = window.findChild<Inspector*>();
    ASSERT_NE(inspector, nullptr);
    inspector->show_element("s30");
    QTest::qWait(200);                               // the layouts settle
    const QWidget* tab = inspector->parentWidget();  // the scroll area's viewport
    ASSERT_NE(tab, nullptr);
    int labels = 0;
    for (const QLabel* label : inspector->findChildren<QLabel*>()) {
        if (!label->isVisible() || label->text().isEmpty()) continue;
        ++labels;
        const QString text = label->textFormat() == Qt::RichText ? QString() : label->text();
        const QPoint right_edge = label->mapTo(tab, label->contentsRect().topRight());
        EXPECT_LT(right_edge.x(), tab->width()) << text.toStdString();
        const QRect needed = label->fontMetrics().boundingRect(
            label->contentsRect(), (label->wordWrap() ? Qt::TextWordWrap : 0) | label->alignment(),
            text);
        EXPECT_LE(needed.width(), label->contentsRect().width()) << text.toStdString();
        EXPECT_LE(needed.height(), label->contentsRect().height()) << text.toStdString();
    }
    EXPECT_GE(labels, 5) << "a title, field names, a margin, the stability line";
}

TEST(Studio, TheLibraryListsTheShippedStrings) {
    MainWindow window(engine_options());
    window.set_resources_folder(QString::fromStdString(test::resource("").string()));
    EXPECT_EQ(window.library().shipped_count(), 16) << "8 full-bandwidth strings and the paper's 8";
}

TEST(Studio, SoundExamplesRenderWithProgressAndCancel) {
    const auto dir = test::temp_dir("studio-examples");
    SoundExamplesDialog dialog(QString::fromStdString(test::resource("").string()),
                               QString::fromStdString((dir / "all").string()));
    int rendered = -1;
    QString error;
    QObject::connect(&dialog, &SoundExamplesDialog::finished_rendering,
                     [&](int n, const QString& e) { rendered = n, error = e; });
    dialog.start();
    ASSERT_TRUE(wait_until([&] { return rendered >= 0; }, 300000));
    const int all = static_cast<int>(sound_examples().size());
    EXPECT_EQ(rendered, all) << error.toStdString();
    EXPECT_EQ(QDir(QString::fromStdString((dir / "all").string())).entryList({"*.wav"}).size(),
              all);

    SoundExamplesDialog cancelled(QString::fromStdString(test::resource("").string()),
                                  QString::fromStdString((dir / "some").string()));
    rendered = -1;
    QObject::connect(&cancelled, &SoundExamplesDialog::finished_rendering,
                     [&](int n, const QString& e) { rendered = n, error = e; });
    cancelled.start();
    cancelled.cancel();
    ASSERT_TRUE(wait_until([&] { return rendered >= 0; }, 60000));
    EXPECT_LT(rendered, all);
    EXPECT_EQ(error, "cancelled");
}

TEST(Studio, ThePadMapsTheMouseToTheBow) {
    GesturePad pad;
    pad.resize(400, 260);
    double slide = 1, press = 1;
    QObject::connect(&pad, &GesturePad::moved, [&](double s, double p) { slide = s, press = p; });
    // The pad's area is inset 12 px at the sides and bottom and 36 px at the top.
    const QPoint centre(200, 36 + (260 - 36 - 12) / 2);
    QTest::mousePress(&pad, Qt::LeftButton, {}, centre);
    EXPECT_NEAR(slide, 0.0, 1e-9);
    const double middle = (GesturePad::kPressMin + GesturePad::kPressMax) / 2;
    EXPECT_NEAR(press, middle, 1e-12);
    QTest::mouseMove(&pad, centre + QPoint(100, 0));  // dragging
    EXPECT_NEAR(slide, 100.0 / 376 * 2 * GesturePad::kSlideRange, 1e-9);
    QTest::mouseRelease(&pad, Qt::LeftButton, {}, centre + QPoint(100, 0));
    EXPECT_EQ(press, 0.0) << "letting go lifts the bow off the string";
    QTest::mouseMove(&pad, centre);  // no button held: the bow stays
    EXPECT_NEAR(slide, 100.0 / 376 * 2 * GesturePad::kSlideRange, 1e-9);
    // Shift held as the mouse lets go keeps the bow pressed.
    QTest::mousePress(&pad, Qt::LeftButton, {}, centre);
    QTest::mouseRelease(&pad, Qt::LeftButton, Qt::ShiftModifier, centre);
    EXPECT_NEAR(press, middle, 1e-12);
    QWheelEvent up(QPointF(200, 100), QPointF(200, 100), {}, QPoint(0, 120), Qt::NoButton, {},
                   Qt::NoScrollPhase, false);
    QApplication::sendEvent(&pad, &up);
    EXPECT_NEAR(press, middle - 0.0001, 1e-9) << "the wheel lifts the bow a tenth of a mm";
    pad.set_position(1.0, 1.0);
    EXPECT_EQ(slide, GesturePad::kSlideRange) << "clamped to the pad";
    EXPECT_EQ(press, GesturePad::kPressMax);
}

}  // namespace
}  // namespace archet::ui
