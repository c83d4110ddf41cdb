#pragma once
// The main window of `archipelago`.

#include <QMainWindow>

namespace archipelago::ui {

class MainWindow : public QMainWindow {
  Q_OBJECT
 public:
  explicit MainWindow(QWidget* parent = nullptr);

 private:
  void createMenus();
  void showAbout();
};

}  // namespace archipelago::ui
