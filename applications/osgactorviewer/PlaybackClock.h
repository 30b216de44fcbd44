/* osgactorviewer: the simulation time the viewer shows, with play/pause, speed and scrubbing. */
#ifndef OSGACTORVIEWER_PLAYBACKCLOCK_H
#define OSGACTORVIEWER_PLAYBACKCLOCK_H 1

namespace osgActorViewer {

/** Simulation time in seconds, advanced by the wall-clock time between frames times the speed while playing.
  * Every controller (clips, trajectories, gaits) reads it from the frame stamp, so pausing freezes them all. */
class PlaybackClock
{
public:
    /** Advances by elapsedSeconds of wall-clock time times the speed (nothing while paused or when negative). A
      * stall (loading, the first frame's shader compilation) counts as at most kMaxStepSeconds, so that the
      * animation does not jump. */
    void advance(double elapsedSeconds);

    double getTime() const { return _time; }
    void setTime(double seconds) { _time = seconds < 0.0 ? 0.0 : seconds; }

    bool isPlaying() const { return _playing; }
    void setPlaying(bool playing) { _playing = playing; }
    void togglePlaying() { _playing = !_playing; }

    /** Speed factor, kept within [1/64, 64]. */
    double getSpeed() const { return _speed; }
    void setSpeed(double speed);

    /** Pauses and moves by a number of steps of stepSeconds (negative: backwards; time never goes below 0). */
    void scrub(int steps);
    static constexpr double kStepSeconds = 1.0 / 30.0;
    static constexpr double kMaxStepSeconds = 0.1;

private:
    double _time = 0.0;
    double _speed = 1.0;
    bool _playing = true;
};

} // namespace osgActorViewer

#endif
