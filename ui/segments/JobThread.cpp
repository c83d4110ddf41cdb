#include "ui/segments/JobThread.hpp"

#include <QMutexLocker>

namespace archipelago::ui {

JobThread::JobThread(QObject* parent) : QThread(parent) {}

JobThread::~JobThread() {
  {
    QMutexLocker lock(&mutex_);
    abort_ = true;
    queue_.clear();
    queued_ = 0;
    current_.request_stop();
    wake_.wakeOne();
  }
  wait();
}

void JobThread::submit(Job job, bool urgent) {
  QMutexLocker lock(&mutex_);
  if (urgent)
    queue_.push_front(std::move(job));
  else
    queue_.push_back(std::move(job));
  queued_ = static_cast<int>(queue_.size());
  if (!isRunning())
    start(QThread::LowPriority);
  else
    wake_.wakeOne();
}

void JobThread::cancelAll() {
  QMutexLocker lock(&mutex_);
  queue_.clear();
  queued_ = 0;
  current_.request_stop();
}

void JobThread::run() {
  for (;;) {
    Job job;
    std::stop_token token;
    {
      QMutexLocker lock(&mutex_);
      while (queue_.empty() && !abort_) wake_.wait(&mutex_);
      if (abort_) return;
      running_ = true;  // before queued_ drops, so that idle() never sees a job in neither place
      job = std::move(queue_.front());
      queue_.pop_front();
      queued_ = static_cast<int>(queue_.size());
      current_ = std::stop_source();  // a fresh source: cancelAll() before this point does not stop this job
      token = current_.get_token();
    }
    job(token);
    running_ = false;
  }
}

}  // namespace archipelago::ui
