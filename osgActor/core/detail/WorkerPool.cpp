#include <osgActor/core/detail/WorkerPool>

#include <algorithm>
#include <cstdint>

namespace osgActor {

WorkerPool::WorkerPool(unsigned numThreads, std::function<void()> onWorkerStart)
{
    if (numThreads == 0) numThreads = std::max(1u, std::thread::hardware_concurrency());
    _slices.reset(new Slice[numThreads]);
    for (unsigned i = 1; i < numThreads; ++i)
        _workers.emplace_back([this, i, onWorkerStart] {
            if (onWorkerStart) onWorkerStart();
            workerLoop(i);
        });
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

void WorkerPool::runItems(unsigned thread)
{
    const unsigned numThreads = getNumThreads();
    for (unsigned k = 0; k < numThreads; ++k) // its own slice first, then the others' in turn
    {
        Slice& slice = _slices[(thread + k) % numThreads];
        for (;;)
        {
            const unsigned begin = slice.next.fetch_add(_grain, std::memory_order_relaxed);
            if (begin >= slice.end) break;
            const unsigned end = std::min(slice.end, begin + _grain);
            for (unsigned i = begin; i < end; ++i) (*_task)(i, thread);
        }
    }
}

void WorkerPool::workerLoop(unsigned thread)
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
        runItems(thread);
        {
            std::lock_guard<std::mutex> lock(_mutex);
            if (--_busyWorkers == 0) _finished.notify_one();
        }
    }
}

void WorkerPool::parallelFor(unsigned count, const std::function<void(unsigned)>& task, unsigned grain)
{
    parallelForWithThread(count, [&task](unsigned i, unsigned) { task(i); }, grain);
}

void WorkerPool::parallelForWithThread(unsigned count, const std::function<void(unsigned, unsigned)>& task,
                                       unsigned grain)
{
    if (count == 0) return;
    if (_workers.empty() || count <= grain)
    {
        for (unsigned i = 0; i < count; ++i) task(i, 0);
        return;
    }
    {
        std::lock_guard<std::mutex> lock(_mutex);
        _task = &task;
        _grain = std::max(1u, grain);
        const unsigned numThreads = getNumThreads();
        const auto sliceStart = [&](unsigned slice) {
            return static_cast<unsigned>(std::uint64_t(count) * slice / numThreads);
        };
        for (unsigned t = 0; t < numThreads; ++t)
        {
            // Published to the workers by the mutex, as the task is.
            _slices[t].next.store(sliceStart(t), std::memory_order_relaxed);
            _slices[t].end = sliceStart(t + 1);
        }
        _busyWorkers = static_cast<unsigned>(_workers.size());
        ++_generation;
    }
    _wake.notify_all();
    runItems(0);
    // Every worker must have left runItems() before the task (owned by the caller) goes out of scope.
    std::unique_lock<std::mutex> lock(_mutex);
    _finished.wait(lock, [&] { return _busyWorkers == 0; });
    _task = nullptr;
}

} // namespace osgActor
