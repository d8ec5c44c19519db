#pragma once
// Shared by the studio's suites: waiting on the Qt event loop for a condition.

#include <QElapsedTimer>
#include <QTest>
#include <functional>

#include "archet/ui/engine_client.hpp"

namespace archet::test {

/// A studio with no engine to start: the editor and panels alone.
inline ui::EngineClientOptions editor_alone() {
    ui::EngineClientOptions options;
    options.archet_binary = "/nonexistent/archet";
    return options;
}

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
