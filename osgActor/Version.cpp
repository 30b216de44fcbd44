#include <osgActor/Version>

namespace osgActor {

const char* getVersion() { return OSGACTOR_VERSION_STRING; }

} // namespace osgActor
