#include "ui/portrait/OverflowToolBar.hpp"

#include <QAction>
#include <QEvent>
#include <QFrame>
#include <QMenu>
#include <QResizeEvent>
#include <QStyle>
#include <QToolButton>

#include <algorithm>

namespace archipelago::ui {

OverflowToolBar::OverflowToolBar(QWidget* parent) : QWidget(parent) {
  setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Fixed);
  overflow_ = new QToolButton(this);
  overflow_->setObjectName(QStringLiteral("overflowButton"));
  overflow_->setText(QStringLiteral("»"));
  overflow_->setToolTip(tr("More portrait controls (all of them are also in the Portrait menu)"));
  overflow_->setAutoRaise(true);
  overflow_->setPopupMode(QToolButton::InstantPopup);
  overflow_->setStyleSheet(QStringLiteral("QToolButton::menu-indicator { image: none; width: 0; }"));
  menu_ = new QMenu(overflow_);
  overflow_->setMenu(menu_);
  connect(menu_, &QMenu::aboutToShow, this, &OverflowToolBar::fillMenu);
  overflow_->hide();
}

void OverflowToolBar::addItem(QWidget* widget, QAction* equivalent) {
  widget->setParent(this);
  items_.push_back({widget, equivalent, false});
  relayout();
}

QToolButton* OverflowToolBar::addAction(QAction* action) {
  auto* button = new QToolButton(this);
  button->setDefaultAction(action);
  button->setAutoRaise(true);
  button->setToolButtonStyle(Qt::ToolButtonTextOnly);
  addItem(button, action);
  return button;
}

void OverflowToolBar::addSeparator() {
  auto* line = new QFrame(this);
  line->setFrameShape(QFrame::VLine);
  line->setFrameShadow(QFrame::Sunken);
  items_.push_back({line, nullptr, true});
  relayout();
}

std::vector<QAction*> OverflowToolBar::overflowActions() const {
  std::vector<QAction*> actions;
  for (const Item& item : items_)
    if (item.widget && item.widget->isHidden() && item.equivalent) actions.push_back(item.equivalent);
  return actions;
}

QSize OverflowToolBar::sizeHint() const {
  int width = 0, height = overflow_->sizeHint().height();
  for (const Item& item : items_) {
    if (!item.widget) continue;
    const QSize s = item.widget->sizeHint();
    width += s.width() + spacing_;
    height = std::max(height, s.height());
  }
  return {width + 4, height + 4};
}

QSize OverflowToolBar::minimumSizeHint() const { return {overflow_->sizeHint().width() + 4, sizeHint().height()}; }

void OverflowToolBar::resizeEvent(QResizeEvent* event) {
  QWidget::resizeEvent(event);
  relayout();
}

bool OverflowToolBar::event(QEvent* event) {
  // A child that changes its size hint (a combo box's longer item, a button's new text) lays the bar out again.
  if (event->type() == QEvent::LayoutRequest) relayout();
  return QWidget::event(event);
}

void OverflowToolBar::relayout() {
  const int height = this->height() > 0 ? this->height() : sizeHint().height();
  const int available = width() - 2;
  const int buttonWidth = overflow_->sizeHint().width();
  int total = 0;
  for (const Item& item : items_)
    if (item.widget) total += item.widget->sizeHint().width() + spacing_;
  const bool overflowing = total > available;
  const int limit = overflowing ? available - buttonWidth - spacing_ : available;
  int x = 2;
  bool full = false;
  for (Item& item : items_) {
    if (!item.widget) continue;
    const QSize s = item.widget->sizeHint();
    if (!full && x + s.width() <= limit) {
      item.widget->setGeometry(x, (height - s.height()) / 2, s.width(), s.height());
      item.widget->show();
      x += s.width() + spacing_;
    } else {
      full = true;  // everything after the first item that does not fit goes behind »
      item.widget->hide();
    }
  }
  overflow_->setVisible(overflowing);
  if (overflowing) {
    const QSize s = overflow_->sizeHint();
    overflow_->setGeometry(width() - s.width() - 1, (height - s.height()) / 2, s.width(), s.height());
    overflow_->raise();
  }
}

void OverflowToolBar::fillMenu() {
  menu_->clear();
  bool separatorDue = false;
  for (const Item& item : items_) {
    if (!item.widget || !item.widget->isHidden()) continue;
    if (item.separator) {
      separatorDue = !menu_->isEmpty();
      continue;
    }
    if (!item.equivalent) continue;
    if (separatorDue) menu_->addSeparator();
    separatorDue = false;
    menu_->addAction(item.equivalent);
  }
}

}  // namespace archipelago::ui
