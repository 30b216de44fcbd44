#include "ProgressBar.h"

#include <unistd.h>

namespace osgActorRender {

ProgressBar::ProgressBar(unsigned total, bool enabled, std::FILE* stream)
    : _total(total), _done(0), _enabled(enabled), _finished(false), _stream(stream),
      _start(std::chrono::steady_clock::now())
{
}

bool ProgressBar::isTerminal(std::FILE* stream) { return isatty(fileno(stream)) != 0; }

void ProgressBar::step()
{
    ++_done;
    if (_enabled) draw();
}

void ProgressBar::finish()
{
    if (!_enabled || _finished) return;
    _finished = true;
    std::fputc('\n', _stream);
    std::fflush(_stream);
}

void ProgressBar::draw() const
{
    const int kWidth = 30;
    const int filled = _total > 0 ? int(kWidth * double(_done) / _total) : kWidth;
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - _start).count();
    std::fprintf(_stream, "\r[");
    for (int i = 0; i < kWidth; ++i) std::fputc(i < filled ? '#' : '.', _stream);
    std::fprintf(_stream, "] %u/%u frames  %.1f ms/frame", _done, _total, _done > 0 ? 1000.0 * seconds / _done : 0.0);
    std::fflush(_stream);
}

} // namespace osgActorRender
