#pragma once
// Private: the BVH build's task pool. Subtree builds are pushed as tasks whenever a node is
// large enough, at any depth, and idle threads take them: with a fixed spawn depth a single
// large subtree below it kept one core busy while the other waited at the end of the build.
// Tasks never wait for one another (results that need both children are fixed up after
// run()), so there are no joins and no deadlocks.

#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace mvcl::detail {

class TaskPool {
public:
    using Task = std::function<void()>;

    /// Queues a task; callable from inside tasks.
    void push(Task task) {
        {
            std::lock_guard<std::mutex> lock(m_mutex);
            m_tasks.push_back(std::move(task));
            ++m_pending;
        }
        m_wake.notify_one();
    }

    /// Runs `first` and every task pushed until none is left, on `threads` threads (the
    /// caller's included).
    void run(int threads, Task first) {
        push(std::move(first));
        std::vector<std::thread> helpers;
        for (int t = 1; t < threads; ++t) helpers.emplace_back([this] { work(); });
        work();
        for (std::thread &t : helpers) t.join();
    }

private:
    void work() {
        std::unique_lock<std::mutex> lock(m_mutex);
        for (;;) {
            m_wake.wait(lock, [this] { return !m_tasks.empty() || m_pending == 0; });
            if (m_tasks.empty()) return; // nothing queued or running: all done
            // Newest first: it is the smallest and its data are still in cache.
            Task task = std::move(m_tasks.back());
            m_tasks.pop_back();
            lock.unlock();
            task();
            lock.lock();
            if (--m_pending == 0) m_wake.notify_all();
        }
    }

    std::mutex m_mutex;
    std::condition_variable m_wake;
    std::vector<Task> m_tasks;
    std::size_t m_pending = 0; ///< queued plus running
};

} // namespace mvcl::detail
