#include "PoseCrowd"

#include "BenchHumanoid"

#include <osgActor/core/ClipPlayer>

namespace bench {

PoseCrowd::PoseCrowd(unsigned numActors)
    : _poses(numActors, osgActor::ActorPose(humanoidDefinition())), _transforms(numActors), _players(numActors)
{
    for (unsigned a = 0; a < numActors; ++a)
    {
        auto player = std::make_shared<osgActor::ClipPlayer>(humanoidOsgActorClip());
        player->setPlayMode(osgActor::PlayMode::Loop);
        player->seek(0.01 * a);
        player->play();
        _players[a].push_back(player);
    }
    _context.deltaTime = 1.0 / 60.0;
}

void PoseCrowd::frame()
{
    _context.time += _context.deltaTime;
    for (std::size_t a = 0; a < _poses.size(); ++a)
    {
        osgActor::ControllerTarget target{_poses[a], _transforms[a]};
        osgActor::runControllers(_players[a], _context, target);
        _poses[a].updateMatrices();
    }
}

} // namespace bench
