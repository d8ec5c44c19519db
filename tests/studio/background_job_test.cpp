// The studio's background job under Qt's offscreen platform: the work runs off the GUI thread,
// its progress and then its result arrive on the GUI thread, an error arrives as its message,
// cancel stops a long job, a busy job starts nothing else, and destroying a running job
// cancels and joins it without delivering anything.

#include <gtest/gtest.h>

#include <QCoreApplication>
#include <QThread>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <memory>
#include <optional>
#include <stdexcept>
#include <thread>
#include <vector>

#include "archet/ui/background_job.hpp"
#include "studio_test_support.hpp"

namespace archet::ui {
namespace {

using Control = BackgroundJob::Control;
using test::wait_until;

bool on_gui_thread() {
    return QThread::currentThread() == QCoreApplication::instance()->thread();
}

// Works until cancelled, up to a minute; says whether it was cancelled.
bool work_until_cancelled(Control& control) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::minutes(1);
    for (std::size_t n = 1; std::chrono::steady_clock::now() < until; ++n) {
        if (control.cancelled()) return true;
        control.progress(n, 0);
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    return false;
}

TEST(BackgroundJob, ProgressThenTheResultArriveOnTheGuiThread) {
    BackgroundJob job;
    std::vector<std::size_t> progress;
    bool progress_on_gui = true;
    QObject::connect(&job, &BackgroundJob::progressed, [&](std::size_t done, std::size_t total) {
        progress.push_back(done);
        progress_on_gui = progress_on_gui && on_gui_thread();
        EXPECT_EQ(total, 5u);
    });
    std::atomic<bool> worked_on_gui{true};
    int result = 0;
    bool result_on_gui = false, finished = false;
    std::size_t progress_before_result = 0;
    QObject::connect(&job, &BackgroundJob::finished, [&] { finished = true; });
    ASSERT_TRUE(job.start(
        [&](Control& control) {
            worked_on_gui = on_gui_thread();
            for (std::size_t n = 1; n <= 5; ++n) {
                std::this_thread::sleep_for(std::chrono::milliseconds(20));
                control.progress(n, 5);
            }
            return 42;
        },
        [&](int r) {
            result = r, result_on_gui = on_gui_thread();
            progress_before_result = progress.empty() ? 0 : progress.back();
        },
        [](const QString& error) { ADD_FAILURE() << error.toStdString(); }));
    EXPECT_TRUE(job.busy());
    ASSERT_TRUE(wait_until([&] { return finished; }, 60000));
    EXPECT_FALSE(worked_on_gui) << "the work ran off the GUI thread";
    EXPECT_EQ(result, 42);
    EXPECT_TRUE(result_on_gui);
    EXPECT_TRUE(progress_on_gui);
    ASSERT_FALSE(progress.empty());
    EXPECT_EQ(progress_before_result, 5u) << "the newest progress arrives before the result";
    EXPECT_TRUE(std::is_sorted(progress.begin(), progress.end()));
    EXPECT_FALSE(job.busy());
}

TEST(BackgroundJob, AnErrorArrivesAsItsMessageAndTheJobCanRunAgain) {
    BackgroundJob job;
    QString error;
    bool error_on_gui = false;
    ASSERT_TRUE(job.start([](Control&) -> int { throw std::runtime_error("no such string"); },
                          [](int) { ADD_FAILURE() << "no result from a job that threw"; },
                          [&](const QString& e) { error = e, error_on_gui = on_gui_thread(); }));
    ASSERT_TRUE(wait_until([&] { return !job.busy(); }, 60000));
    EXPECT_EQ(error, "no such string");
    EXPECT_TRUE(error_on_gui);
    int again = 0;
    ASSERT_TRUE(
        job.start([](Control&) { return 7; }, [&](int r) { again = r; }, [](const QString&) {}));
    ASSERT_TRUE(wait_until([&] { return again == 7; }, 60000));
}

TEST(BackgroundJob, CancelStopsALongJobAndABusyJobStartsNothingElse) {
    BackgroundJob job;
    std::size_t seen = 0;
    QObject::connect(&job, &BackgroundJob::progressed, [&](std::size_t done) { seen = done; });
    std::optional<bool> cancelled;
    ASSERT_TRUE(job.start(
        work_until_cancelled, [&](bool c) { cancelled = c; },
        [](const QString& e) { ADD_FAILURE() << e.toStdString(); }));
    bool second_ran = false;
    EXPECT_FALSE(job.start([](Control&) { return 0; }, [&](int) { second_ran = true; },
                           [](const QString&) {}))
        << "one job at a time";
    ASSERT_TRUE(wait_until([&] { return seen > 0; }, 60000)) << "it is under way";
    const auto asked = std::chrono::steady_clock::now();
    job.cancel();
    ASSERT_TRUE(wait_until([&] { return cancelled.has_value(); }, 60000));
    EXPECT_TRUE(*cancelled) << "it stopped because it was asked, not at its minute";
    EXPECT_LT(std::chrono::steady_clock::now() - asked, std::chrono::seconds(30));
    EXPECT_FALSE(second_ran);
}

TEST(BackgroundJob, DestroyingARunningJobCancelsAndJoinsItAndDeliversNothing) {
    auto job = std::make_unique<BackgroundJob>();
    std::atomic<bool> started{false}, ended{false};
    bool delivered = false;
    ASSERT_TRUE(job->start(
        [&](Control& control) {
            started = true;
            const bool cancelled = work_until_cancelled(control);
            ended = true;
            return cancelled;
        },
        [&](bool) { delivered = true; }, [&](const QString&) { delivered = true; }));
    ASSERT_TRUE(wait_until([&] { return started.load(); }, 60000));
    job.reset();
    EXPECT_TRUE(ended) << "the worker was joined before the job went";
    QCoreApplication::processEvents();
    QCoreApplication::sendPostedEvents();
    EXPECT_FALSE(delivered) << "nothing reaches handlers of a job that is gone";
}

}  // namespace
}  // namespace archet::ui
