#pragma once
// One long computation at a time off the GUI thread, for the studio's offline work (the compare
// view's renders, the playability map, the sound examples). The work runs on a worker thread
// with a Control: it reports progress and polls for cancel through it. Progress, the result
// and any error arrive on the GUI thread through queued calls, so handlers may touch widgets.
// Destroying the job cancels it and joins the worker; what it had still queued is dropped with
// it. A job that captures its owner's members must therefore be the owner's last member (or be
// destroyed first), so that it joins before they go.

#include <QObject>
#include <QString>
#include <atomic>
#include <cstddef>
#include <functional>
#include <memory>
#include <thread>
#include <type_traits>
#include <utility>

namespace archet::ui {

class BackgroundJob : public QObject {
    Q_OBJECT

  public:
    /// What the work sees. Thread-safe; the work may hand it to its own threads.
    class Control {
      public:
        /// Reports `done` of `total`. Calls are coalesced: the GUI thread gets the newest.
        void progress(std::size_t done, std::size_t total);
        bool cancelled() const { return cancel_.load(std::memory_order_relaxed); }
        /// For computations that poll a flag themselves (play_map).
        const std::atomic<bool>& cancel_flag() const { return cancel_; }

      private:
        friend class BackgroundJob;
        explicit Control(BackgroundJob& job) : job_(job) {}
        BackgroundJob& job_;
        std::atomic<bool> cancel_{false}, progress_queued_{false};
        std::atomic<std::size_t> done_{0}, total_{0};
    };

    explicit BackgroundJob(QObject* parent = nullptr);
    ~BackgroundJob() override;

    /// Runs `work(control)` on a worker thread, then on the GUI thread `done(result)`, or
    /// `failed(message)` if the work threw. While a job is busy, starts nothing and returns
    /// false.
    template <typename Work, typename Done, typename Failed>
    bool start(Work work, Done done, Failed failed);

    /// Asks the running work to stop; it ends when it next looks at its Control.
    void cancel();
    /// From start() until its result or error has been delivered on the GUI thread.
    bool busy() const { return busy_; }

  signals:
    /// On the GUI thread, the newest progress the work reported.
    void progressed(std::size_t done, std::size_t total);
    /// On the GUI thread, after `done` or `failed` ran.
    void finished();

  private:
    using Delivery = std::function<void()>;  ///< run on the GUI thread when the work ends
    bool run(std::function<Delivery(Control&)> work, std::function<void(const QString&)> failed);
    void deliver_progress();
    void join();

    std::unique_ptr<Control> control_;  ///< the running (or last) work's
    std::thread worker_;
    bool busy_ = false;  ///< GUI thread only
};

template <typename Work, typename Done, typename Failed>
bool BackgroundJob::start(Work work, Done done, Failed failed) {
    using Result = std::invoke_result_t<Work&, Control&>;
    return run(
        [work = std::move(work), done = std::move(done)](Control& control) mutable -> Delivery {
            // Shared: std::function copies its target, and a result need not be copyable.
            auto result = std::make_shared<Result>(work(control));
            return [done, result]() mutable { done(std::move(*result)); };
        },
        std::move(failed));
}

}  // namespace archet::ui
