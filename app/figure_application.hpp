#pragma once
// The Qt application a command needs to draw a figure with the studio's widgets; without a
// display it draws offscreen.

#include <QApplication>
#include <memory>

namespace archet::cli {

class FigureApplication {
  public:
    FigureApplication();

  private:
    int argc_ = 1;
    char name_[7] = "archet";
    char* argv_[2] = {name_, nullptr};
    std::unique_ptr<QApplication> app_;
};

}  // namespace archet::cli
