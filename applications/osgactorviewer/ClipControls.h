/* osgactorviewer: choosing which of an actor's clips plays. */
#ifndef OSGACTORVIEWER_CLIPCONTROLS_H
#define OSGACTORVIEWER_CLIPCONTROLS_H 1

#include <osgActor/ActorNode>
#include <osgActor/core/ClipPlayer>

#include <memory>
#include <string>

namespace osgActorViewer {

/** The actor's first clip player (as readMocapActor and the .actor clips add them), or null. */
std::shared_ptr<osgActor::ClipPlayer> findClipPlayer(const osgActor::ActorNode& actor);

/** Plays the next (step +1) or previous (-1) clip of the actor's clip library, in name order, from its start, on
  * the actor's clip player (one is added, looping, when the actor has clips but no player). Returns what happened,
  * for the panel. */
std::string switchClip(osgActor::ActorNode& actor, int step);

/** "walk 1.25 / 2.40 s", or "none". */
std::string describeClip(const osgActor::ActorNode& actor);

} // namespace osgActorViewer

#endif
