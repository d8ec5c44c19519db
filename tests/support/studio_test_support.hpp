#pragma once
// Shared by the studio's suites: waiting on the Qt event loop for a condition.

#include <QElapsedTimer>
#include <QTest>
#include <functional>

namespace archet::test {

/// Runs the event loop until `done` holds or `ms` pass; returns its last answer.
inline bool wait_until(const std::function<bool()>& done, int ms) {
    QElapsedTimer clock;
    clock.start();
    while (clock.elapsed() < ms) {
        if (done()) return true;
        QTest::qWait(10);
    }
    return done();
}

}  // namespace archet::test
