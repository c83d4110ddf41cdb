#include "ui/window/HelpDialogs.hpp"

#include <QAction>
#include <QDialog>
#include <QDialogButtonBox>
#include <QHeaderView>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QScreen>
#include <QStringList>
#include <QTableWidget>
#include <QVBoxLayout>
#include <qwt_global.h>

#include <algorithm>
#include <functional>

#include "ui/run/RunWorker.hpp"

namespace archipelago::ui {

namespace {
/// The keys of every action of `menu` and its submenus, each by its menu path from `path`.
void addMenuKeys(const QMenu& menu, const QString& path, QList<QPair<QString, QString>>& rows) {
  for (QAction* a : menu.actions()) {
    if (a->isSeparator()) continue;
    const QString name = path + QStringLiteral(" ▸ ") + QString(a->text()).remove(QLatin1Char('&'));
    if (a->menu()) {
      addMenuKeys(*a->menu(), name, rows);
      continue;
    }
    QStringList keys;
    for (const QKeySequence& k : a->shortcuts()) keys << k.toString(QKeySequence::NativeText);
    if (!keys.isEmpty()) rows.append({name, keys.join(QStringLiteral(", "))});
  }
}

/// The table of the dialog: the Action column as wide as its longest entry, the Keys column the rest, its long
/// entries (the mouse's) wrapped onto more lines (issue 53, finding 23: the Action column was squeezed and cut).
QTableWidget* shortcutsTable(const QList<QPair<QString, QString>>& rows, QWidget* parent) {
  auto* table = new QTableWidget(static_cast<int>(rows.size()), 2, parent);
  table->setHorizontalHeaderLabels({QObject::tr("Action"), QObject::tr("Keys")});
  table->verticalHeader()->hide();
  table->setEditTriggers(QAbstractItemView::NoEditTriggers);
  for (int i = 0; i < rows.size(); ++i) {
    table->setItem(i, 0, new QTableWidgetItem(rows[i].first));
    table->setItem(i, 1, new QTableWidgetItem(rows[i].second));
  }
  table->setWordWrap(true);
  table->horizontalHeader()->setSectionResizeMode(0, QHeaderView::ResizeToContents);
  table->horizontalHeader()->setSectionResizeMode(1, QHeaderView::Stretch);
  table->verticalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  table->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  return table;
}
}  // namespace

QList<QPair<QString, QString>> keyboardShortcuts(const QMenuBar& bar) {
  QList<QPair<QString, QString>> rows;
  // Every action of every menu, by its menu path: the one list of keys (a menu item shows its key too).
  for (QAction* a : bar.actions())
    if (a->menu()) addMenuKeys(*a->menu(), QString(a->text()).remove(QLatin1Char('&')), rows);
  rows.append({QObject::tr("Portrait: click"),
               QObject::tr("launch an orbit (listed under Orbits with its rotation number and chain)")});
  rows.append({QObject::tr("Portrait: Shift+click"),
               QObject::tr("find the periodic orbit there: its island chain named, its elliptic orbit drawn (Portrait ▸ "
                           "Click Finds Periodic Orbits: a plain click too)")});
  rows.append({QObject::tr("Portrait: drag"), QObject::tr("zoom to the rectangle (with the profile tool: draw the line)")});
  rows.append({QObject::tr("Portrait: wheel"), QObject::tr("zoom about the cursor")});
  rows.append({QObject::tr("Portrait: middle-drag"), QObject::tr("pan")});
  rows.append({QObject::tr("Plots: drag / right click / wheel"), QObject::tr("zoom / zoom back / zoom about the cursor")});
  return rows;
}

void showKeyboardShortcuts(QWidget* parent, const QList<QPair<QString, QString>>& rows) {
  auto* dialog = new QDialog(parent);
  dialog->setObjectName(QStringLiteral("keyboardShortcutsDialog"));
  dialog->setWindowTitle(QObject::tr("Keyboard Shortcuts"));
  dialog->setAttribute(Qt::WA_DeleteOnClose);
  QTableWidget* table = shortcutsTable(rows, dialog);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Close, dialog);
  QObject::connect(buttons, &QDialogButtonBox::rejected, dialog, &QDialog::close);
  auto* layout = new QVBoxLayout(dialog);
  layout->addWidget(table);
  layout->addWidget(buttons);
  const int actions = static_cast<QAbstractItemView*>(table)->sizeHintForColumn(0);
  const QRect screen = parent->screen() ? parent->screen()->availableGeometry() : QRect(0, 0, 1280, 800);
  dialog->resize(std::min(actions + parent->fontMetrics().horizontalAdvance(QLatin1Char('x')) * 50 + 60,
                          screen.width() * 9 / 10),
                 std::min(640, screen.height() * 8 / 10));
  dialog->show();
}

void showAbout(QWidget* parent, const QString& kernel) {
  QMessageBox::about(
      parent, QObject::tr("About Archipelago"),
      QObject::tr("<h3>Archipelago %1</h3>"
                  "<p>Exact trapping statistics of the quadratic map Q*: how islands around islands make "
                  "chaotic orbits sticky.</p>"
                  "<p>Reproduces C. F. F. Karney, <i>Long-time correlations in the stochastic regime</i>, "
                  "Physica D <b>8</b>, 360–380 (1983), "
                  "<a href=\"https://doi.org/10.1016/0167-2789(83)90232-6\">doi:10.1016/0167-2789(83)90232-6</a>.</p>"
                  "<table>"
                  "<tr><td>Qt</td><td>%2 (built with %3)</td></tr>"
                  "<tr><td>Qwt</td><td>%4</td></tr>"
                  "<tr><td>Kernel</td><td>%5 — %6</td></tr>"
                  "</table>")
          .arg(QStringLiteral(ARCHIPELAGO_VERSION), QString::fromLatin1(qVersion()), QStringLiteral(QT_VERSION_STR),
               QStringLiteral(QWT_VERSION_STR), kernel, RunWorker::kernelDescription()));
}

}  // namespace archipelago::ui
