// Internal to the library (not installed, NOT API): an actor's bound computed on one of its group's threads, where
// that writes nothing another thread may touch. OSG computes bounds lazily, on whichever thread first asks, and the
// nodes below an actor may be shared with other actors (a geode, a skinned mesh, a user's subtree). ActorGroup asks
// its actors' bounds on its threads (ActorGroup::computeBound()) only where every bound the computation would write
// is the actor's own: the actor itself and its skeleton nodes, each of its plain class, with one parent and no
// callback computing its bound. Every other node it would read must hold its bound already, so that no thread writes
// it; the actors that fail the test are left to the serial union that follows, as before.
#ifndef OSGACTOR_DETAIL_OWNBOUNDS_H
#define OSGACTOR_DETAIL_OWNBOUNDS_H 1

namespace osgActor {

class ActorNode;

namespace detail {

/** Computes the actor's bound (getBound()) where the test above holds, and returns whether its bound is now
  * computed (true also where it already was). */
bool computeOwnBound(ActorNode& actor);

} // namespace detail
} // namespace osgActor

#endif
