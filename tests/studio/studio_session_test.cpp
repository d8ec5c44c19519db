// The studio as a place where work is kept, under Qt's offscreen platform with a real engine:
// shipped models are templates (Save writes a copy among the user's documents), every way of
// dropping unsaved edits asks first, the layout and the last model come back after a
// restart, selecting never moves the pad, a model the pad cannot bow says so, a take being
// recorded is shown with its time, the Help menu is there, and the plots follow a light or a
// dark palette. Screenshots of both go to build/test-artifacts/.

#include <gtest/gtest.h>
#include <qcustomplot.h>

#include <QAbstractButton>
#include <QApplication>
#include <QDir>
#include <QFileDialog>
#include <QGraphicsSimpleTextItem>
#include <QLabel>
#include <QLineEdit>
#include <QMenuBar>
#include <QMessageBox>
#include <QSettings>
#include <QSplitter>
#include <QTabWidget>
#include <QTest>
#include <QTimer>
#include <memory>
#include <type_traits>

#include "archet/files/model_file.hpp"
#include "archet/ui/appearance.hpp"
#include "archet/ui/gesture_pad.hpp"
#include "archet/ui/graph_view.hpp"
#include "archet/ui/main_window.hpp"
#include "archet/ui/model_document.hpp"
#include "archet/ui/new_string_dialog.hpp"
#include "archet/ui/scope_panel.hpp"
#include "archet/ui/studio_settings.hpp"
#include "studio_test_support.hpp"
#include "test_support.hpp"

namespace archet::ui {
namespace {

using test::wait_until;

EngineClientOptions engine_options() {
    EngineClientOptions o;
    o.archet_binary = ARCHET_BINARY;
    o.audio = "null";
    return o;
}

// Qt's file dialog restores the state the last one saved (its header's sort among it), and
// Qt 6.4 frees that with the wrong deallocator, which AddressSanitizer stops at. Each dialog
// of these tests starts from no saved state.
void forget_file_dialog_state() {
    QSettings qt(QSettings::UserScope, "QtProject");
    qt.remove("FileDialog");
    qt.remove("Qt/filedialog");
}

// Answers the next modal dialog of type D as soon as it shows, with `answer`; the returned
// flag says whether one showed. The watch belongs to `owner` (the test's fixture): it ends
// with the test, so that it never answers a later test's dialog.
template <typename D>
std::shared_ptr<bool> answer_next(QObject& owner, std::function<void(D&)> answer) {
    if constexpr (std::is_same_v<D, QFileDialog>) forget_file_dialog_state();
    auto shown = std::make_shared<bool>(false);
    auto* poll = new QTimer(&owner);
    auto tries = std::make_shared<int>(0);
    QObject::connect(poll, &QTimer::timeout, [=] {
        // Stopped first: deleteLater() waits for the event loop it was called from, and a
        // modal dialog's loop runs inside it.
        if (auto* dialog = qobject_cast<D*>(QApplication::activeModalWidget())) {
            *shown = true;
            poll->stop();
            poll->deleteLater();
            answer(*dialog);
        } else if (++*tries > 500) {  // 10 s: it never came
            poll->stop();
            poll->deleteLater();
        }
    });
    poll->start(20);
    return shown;
}

class Session : public ::testing::Test {
  protected:
    template <typename D>
    std::shared_ptr<bool> answer_next(std::function<void(D&)> answer) {
        return ui::answer_next<D>(watches, std::move(answer));
    }
    std::shared_ptr<bool> answer_question(QMessageBox::StandardButton button) {
        return answer_next<QMessageBox>([button](QMessageBox& box) {
            if (QAbstractButton* b = box.button(button)) b->click();
        });
    }

    void SetUp() override {
        QSettings().clear();  // test mode: the settings of this suite only
        dir = test::temp_dir(
            "studio-session-" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        window = std::make_unique<MainWindow>(engine_options());
        window->set_autosave_folder(QString::fromStdString((dir / "autosave").string()));
        window->set_documents_folder(QString::fromStdString((dir / "Documents").string()));
        window->set_resources_folder(QString::fromStdString(test::resource("").string()));
        ASSERT_TRUE(window->open_file(shipped_220()));
        window->resize(1400, 900);
        window->show();
        window->activateWindow();
        window->activateWindow();
        ASSERT_TRUE(QTest::qWaitForWindowActive(window.get()));
    }
    static QString shipped_220() {
        return QString::fromStdString(test::resource("models/bowed-string-220.json").string());
    }

    QObject watches;  ///< owns the dialog watches of the test, gone with it
    std::filesystem::path dir;
    std::unique_ptr<MainWindow> window;
};

TEST_F(Session, SavingAShippedModelWritesACopyInTheUsersDocuments) {
    const std::string shipped_bytes = test::read_file(shipped_220().toStdString());
    window->document().edit_parameter({"friction", "mu_s"}, 0.7);
    QString proposed;
    const QString copy = QString::fromStdString((dir / "my-string.json").string());
    auto asked = answer_next<QFileDialog>([&](QFileDialog& d) {
        proposed = d.selectedFiles().value(0);
        // Typed as a user would: the whole path in the file name field (selectFile() races
        // with the dialog filling its folder view in the background).
        auto* name = d.findChild<QLineEdit*>("fileNameEdit");
        ASSERT_NE(name, nullptr);
        name->setText(copy);
        static_cast<QDialog&>(d).accept();  // QFileDialog's own accept() is protected
    });
    QTest::keyClick(window.get(), Qt::Key_S, Qt::ControlModifier);
    ASSERT_TRUE(*asked) << "Ctrl+S on a shipped model asks where to save a copy";
    EXPECT_TRUE(proposed.startsWith(window->documents_folder() + "/models/"))
        << proposed.toStdString();
    EXPECT_TRUE(proposed.endsWith("bowed-string-220.json")) << proposed.toStdString();
    EXPECT_EQ(test::read_file(shipped_220().toStdString()), shipped_bytes) << "untouched";
    ASSERT_TRUE(QFileInfo::exists(copy));
    EXPECT_EQ(load_model_file(copy.toStdString()).find_lia("friction")->mu_static, 0.7);
    EXPECT_FALSE(window->document().modified());
    EXPECT_EQ(window->document().path(), copy);

    // The copy is the user's: Ctrl+S now saves it in place, Ctrl+Shift+S asks anew.
    window->document().edit_parameter({"friction", "mu_s"}, 0.65);
    window->activateWindow();
    ASSERT_TRUE(QTest::qWaitForWindowActive(window.get()));
    QTest::keyClick(window.get(), Qt::Key_S, Qt::ControlModifier);
    EXPECT_EQ(load_model_file(copy.toStdString()).find_lia("friction")->mu_static, 0.65);
    auto save_as = answer_next<QFileDialog>([](QFileDialog& d) { d.reject(); });
    window->activateWindow();
    ASSERT_TRUE(QTest::qWaitForWindowActive(window.get()));
    QTest::keyClick(window.get(), Qt::Key_S, Qt::ControlModifier | Qt::ShiftModifier);
    EXPECT_TRUE(*save_as) << "Ctrl+Shift+S is Save As";
}

TEST_F(Session, EveryWayOfDroppingEditsAsksFirst) {
    window->document().edit_parameter({"friction", "mu_s"}, 0.7);
    const QString other =
        QString::fromStdString(test::resource("models/bowed-string-440.json").string());

    auto asked = answer_question(QMessageBox::Cancel);
    EXPECT_FALSE(window->open_file(other));
    EXPECT_TRUE(*asked) << "opening a file";
    EXPECT_EQ(window->document().model().name, "bowed-string-220") << "cancel keeps the edits";
    EXPECT_TRUE(window->document().modified());

    // New bowed string: cancelled at the question, no dialog for the new string follows.
    asked = answer_question(QMessageBox::Cancel);
    bool new_dialog = false;
    auto no_new = answer_next<NewStringDialog>([&](NewStringDialog& d) {
        new_dialog = true;
        d.reject();
    });
    window->activateWindow();
    ASSERT_TRUE(QTest::qWaitForWindowActive(window.get()));
    QTest::keyClick(window.get(), Qt::Key_N, Qt::ControlModifier);
    EXPECT_TRUE(*asked) << "a new string";
    EXPECT_FALSE(new_dialog);
    EXPECT_EQ(window->document().model().name, "bowed-string-220");

    // Quitting: cancel keeps the window.
    asked = answer_question(QMessageBox::Cancel);
    EXPECT_FALSE(window->close());
    EXPECT_TRUE(*asked) << "quitting";
    EXPECT_TRUE(window->isVisible());

    // Discard: the other model opens.
    asked = answer_question(QMessageBox::Discard);
    EXPECT_TRUE(window->open_file(other));
    EXPECT_TRUE(*asked);
    EXPECT_EQ(window->document().model().name, "bowed-string-440");
}

TEST_F(Session, TheNewestEditIsAutosavedAtOnce) {
    window->document().edit_parameter({"friction", "mu_s"}, 0.71);
    const auto file = dir / "autosave" / "bowed-string-220.json";
    ASSERT_TRUE(wait_until([&] { return std::filesystem::exists(file); }, 60000));
    ASSERT_TRUE(wait_until(
        [&] { return load_model_file(file).find_lia("friction")->mu_static == 0.71; }, 60000));
    window->document().edit_parameter({"friction", "mu_s"}, 0.72);
    EXPECT_TRUE(wait_until(
        [&] { return load_model_file(file).find_lia("friction")->mu_static == 0.72; }, 60000))
        << "the newest edit, not the first";
}

TEST_F(Session, LayoutModelAndAudioSettingsComeBackAfterARestart) {
    auto* tabs = window->findChild<QTabWidget*>();
    ASSERT_NE(tabs, nullptr);
    tabs->setCurrentIndex(2);
    window->resize(1100, 760);
    auto splitters = window->findChildren<QSplitter*>();
    ASSERT_FALSE(splitters.isEmpty());
    QSplitter* split = window->findChild<QSplitter*>("main-side");
    ASSERT_NE(split, nullptr);
    split->setSizes({700, 400});
    window->graph().zoom_to(2.5);
    QTest::qWait(50);
    const QList<int> sizes = split->sizes();
    ASSERT_TRUE(window->close());
    EXPECT_EQ(last_model_path(), QFileInfo(shipped_220()).absoluteFilePath());

    EngineClientOptions o = engine_options();
    o.buffer_frames = 256, o.sample_rate = 44100, o.haptic = "none", o.osc_port = 9000;
    o.midi = "virtual", o.midi_api = "jack", o.midi_map = "/tmp/map.json";
    save_engine_options(o);
    const EngineClientOptions restored = restore_engine_options(engine_options());
    EXPECT_EQ(restored.osc_port, 9000);
    EXPECT_EQ(restored.midi, "virtual");
    EXPECT_EQ(restored.midi_api, "jack");
    EXPECT_EQ(restored.midi_map, "/tmp/map.json");
    EXPECT_EQ(restored.buffer_frames, 256);
    EXPECT_EQ(restored.sample_rate, 44100);
    EXPECT_EQ(restored.haptic, "none");

    MainWindow again(engine_options());
    again.show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(&again));
    EXPECT_EQ(again.size(), QSize(1100, 760));
    EXPECT_EQ(again.findChild<QTabWidget*>()->currentIndex(), 2);
    EXPECT_EQ(again.findChild<QSplitter*>("main-side")->sizes(), sizes);
    ASSERT_TRUE(again.open_file(last_model_path()));  // as archet-studio does with no argument
    again.restore_zoom();
    again.resize(1200, 800);
    QTest::qWait(50);
    EXPECT_DOUBLE_EQ(again.graph().zoom(), 2.5) << "the graph's zoom, kept when resized";
}

TEST_F(Session, SelectingAnElementNeverMovesTheWindowOrThePad) {
    QTest::qWait(100);
    const QRect geometry = window->geometry();
    const QPoint pad = window->pad().mapTo(window.get(), QPoint(0, 0));
    const QSize pad_size = window->pad().size();
    for (const QStringList& ids : {QStringList{"friction"}, QStringList{"bridge"},
                                   QStringList{"hand_slide"}, QStringList{"k30"}, QStringList{}}) {
        window->graph().select(ids);
        QTest::qWait(50);
        EXPECT_EQ(window->geometry(), geometry) << ids.join(",").toStdString();
        EXPECT_EQ(window->pad().mapTo(window.get(), QPoint(0, 0)), pad)
            << ids.join(",").toStdString();
        EXPECT_EQ(window->pad().size(), pad_size) << ids.join(",").toStdString();
    }
}

TEST_F(Session, AModelWithoutAHandSaysSoOnThePad) {
    EXPECT_TRUE(window->pad().notice().isEmpty()) << "the shipped string is bowable";
    Model chain = test::chain(20, 1e-4, 500, 1e-4);
    chain.outputs = {{"m5", Output::Signal::Position, 1.0}};
    window->open_model(chain);
    EXPECT_TRUE(window->pad().notice().contains("no hand")) << window->pad().notice().toStdString();
    ASSERT_TRUE(window->open_file(shipped_220()));
    EXPECT_TRUE(window->pad().notice().isEmpty());
}

TEST_F(Session, ARecordingShowsItsTime) {
    ASSERT_TRUE(
        wait_until([&] { return window->engine().status().model == "bowed-string-220"; }, 60000));
    auto* clock = window->findChild<QLabel*>("recording");
    ASSERT_NE(clock, nullptr);
    EXPECT_FALSE(clock->isVisible());
    QTest::keyClick(window.get(), Qt::Key_R);
    EXPECT_TRUE(clock->isVisible());
    auto seconds = [&] {
        const QString time = clock->text().section("REC ", 1);  // m:ss
        return time.section(':', 0, 0).toInt() * 60 + time.section(':', 1, 1).toInt();
    };
    EXPECT_TRUE(clock->text().contains("REC 0:00")) << clock->text().toStdString();
    EXPECT_TRUE(wait_until([&] { return seconds() >= 1; }, 60000)) << clock->text().toStdString();
    QTest::keyClick(window.get(), Qt::Key_R);
    EXPECT_FALSE(clock->isVisible());
}

TEST_F(Session, TheHelpMenuHasShortcutsTheGuideAndAbout) {
    QMenu* help = nullptr;
    for (QAction* a : window->menuBar()->actions())
        if (a->text() == "&Help") help = a->menu();
    ASSERT_NE(help, nullptr);
    QStringList items;
    for (QAction* a : help->actions()) items << a->text();
    EXPECT_EQ(items, (QStringList{"&Keyboard shortcuts", "&User guide", "&About Archet studio"}));
    QString shown;
    auto asked = answer_next<QMessageBox>([&](QMessageBox& box) {
        shown = box.text();
        box.accept();
    });
    QTest::keyClick(window.get(), Qt::Key_F1);
    EXPECT_TRUE(*asked);
    EXPECT_TRUE(shown.contains("Ctrl+Shift+S")) << shown.toStdString();
}

// Plots in a dark palette are dark with light text, and light in a light one: legible in both.
TEST_F(Session, PlotsFollowALightOrADarkPalette) {
    ASSERT_TRUE(
        wait_until([&] { return window->engine().status().model == "bowed-string-220"; }, 60000));
    QTest::qWait(500);
    for (const auto& [appearance, name] :
         {std::pair{Appearance::Dark, "dark"}, std::pair{Appearance::Light, "light"}}) {
        apply_appearance(appearance);
        QTest::qWait(200);
        const bool dark = appearance == Appearance::Dark;
        for (auto scope : {ScopePanel::Scope::Displacement, ScopePanel::Scope::Spectrum}) {
            QCustomPlot& plot = window->scopes().plot(scope);
            const int background = plot.toPixmap().toImage().pixelColor(3, 3).lightness();
            const int labels = plot.xAxis->tickLabelColor().lightness();
            if (dark)
                EXPECT_LT(background, 80) << name;
            else
                EXPECT_GT(background, 200) << name;
            EXPECT_GT(std::abs(labels - background), 120) << name << ": labels stand out";
            EXPECT_GT(std::abs(plot.graph(0)->pen().color().lightness() - background), 50)
                << name << ": the trace stands out";
        }
        // The graph's labels too.
        const int canvas = window->graph().palette().color(QPalette::Base).lightness();
        ASSERT_FALSE(window->graph().labels().empty());
        for (const auto* label : window->graph().labels())
            EXPECT_GT(std::abs(label->brush().color().lightness() - canvas), 120) << name;
        QDir().mkpath(ARCHET_ARTIFACT_DIR);
        EXPECT_TRUE(window->grab().save(
            QDir(ARCHET_ARTIFACT_DIR).filePath(QString("studio-%1.png").arg(name))));
    }
    apply_appearance(Appearance::Desktop);
}

}  // namespace
}  // namespace archet::ui
