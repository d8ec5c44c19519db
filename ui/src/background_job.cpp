#include "archet/ui/background_job.hpp"

#include <QMetaObject>

namespace archet::ui {

void BackgroundJob::Control::progress(std::size_t done, std::size_t total) {
    done_.store(done, std::memory_order_relaxed);
    total_.store(total, std::memory_order_relaxed);
    // One queued call at a time: a computation on every core may report thousands per second.
    if (!progress_queued_.exchange(true, std::memory_order_acq_rel))
        QMetaObject::invokeMethod(
            &job_, [job = &job_] { job->deliver_progress(); }, Qt::QueuedConnection);
}

BackgroundJob::BackgroundJob(QObject* parent) : QObject(parent) {}

BackgroundJob::~BackgroundJob() {
    cancel();
    join();  // the queued calls still pending go with this object
}

void BackgroundJob::cancel() {
    if (control_) control_->cancel_.store(true);
}

void BackgroundJob::join() {
    if (worker_.joinable()) worker_.join();
}

bool BackgroundJob::run(std::function<Delivery(Control&)> work,
                        std::function<void(const QString&)> failed) {
    if (busy_) return false;
    join();  // the last work has delivered: its thread has ended or is ending
    busy_ = true;
    control_.reset(new Control(*this));
    worker_ = std::thread([this, control = control_.get(), work = std::move(work),
                           failed = std::move(failed)]() mutable {
        Delivery delivery;
        try {
            delivery = work(*control);
        } catch (const std::exception& e) {
            delivery = [failed, message = QString::fromUtf8(e.what())] { failed(message); };
        } catch (...) {  // never out of the thread: that would end the studio
            delivery = [failed] { failed(tr("failed")); };
        }
        // Queued after every progress call the work made, so it arrives after them.
        QMetaObject::invokeMethod(
            this,
            [this, delivery = std::move(delivery)] {
                join();
                busy_ = false;
                delivery();
                emit finished();
            },
            Qt::QueuedConnection);
    });
    return true;
}

void BackgroundJob::deliver_progress() {
    // Acquires the worker's newest report: its counts are seen, or it queues another call.
    control_->progress_queued_.exchange(false, std::memory_order_acq_rel);
    emit progressed(control_->done_.load(), control_->total_.load());
}

}  // namespace archet::ui
