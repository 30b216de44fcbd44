#include <osgActor/core/WorkerPool>

namespace osgActor {

WorkerPool::WorkerPool(unsigned numThreads)
{
    if (numThreads == 0) numThreads = std::max(1u, std::thread::hardware_concurrency());
    for (unsigned i = 1; i < numThreads; ++i) _workers.emplace_back([this] { workerLoop(); });
}

WorkerPool::~WorkerPool()
{
    {
        std::lock_guard<std::mutex> lock(_mutex);
        _stopping = true;
    }
    _wake.notify_all();
    for (std::thread& worker : _workers) worker.join();
}

void WorkerPool::runItems()
{
    for (;;)
    {
        const unsigned begin = _next.fetch_add(_grain, std::memory_order_relaxed);
        if (begin >= _count) return;
        const unsigned end = std::min(_count, begin + _grain);
        for (unsigned i = begin; i < end; ++i) (*_task)(i);
    }
}

void WorkerPool::workerLoop()
{
    unsigned seen = 0;
    for (;;)
    {
        {
            std::unique_lock<std::mutex> lock(_mutex);
            _wake.wait(lock, [&] { return _stopping || _generation != seen; });
            if (_stopping) return;
            seen = _generation;
        }
        runItems();
        {
            std::lock_guard<std::mutex> lock(_mutex);
            if (--_busyWorkers == 0) _finished.notify_one();
        }
    }
}

void WorkerPool::parallelFor(unsigned count, const std::function<void(unsigned)>& task, unsigned grain)
{
    if (count == 0) return;
    if (_workers.empty() || count <= grain)
    {
        for (unsigned i = 0; i < count; ++i) task(i);
        return;
    }
    {
        std::lock_guard<std::mutex> lock(_mutex);
        _task = &task;
        _count = count;
        _grain = std::max(1u, grain);
        _next.store(0, std::memory_order_relaxed);
        _busyWorkers = static_cast<unsigned>(_workers.size());
        ++_generation;
    }
    _wake.notify_all();
    runItems();
    // Every worker must have left runItems() before the task (owned by the caller) goes out of scope.
    std::unique_lock<std::mutex> lock(_mutex);
    _finished.wait(lock, [&] { return _busyWorkers == 0; });
    _task = nullptr;
}

} // namespace osgActor
