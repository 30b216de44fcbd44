/* osgActor, not installed: finds the one osg::Object wrapper that stands for a core object shared by many actors
 * (a definition, a clip library), so that osgDB, which recognises an object it has written by its address, writes
 * the shared object once. */
#ifndef OSGACTOR_SHAREDOBJECTREGISTRY_H
#define OSGACTOR_SHAREDOBJECTREGISTRY_H 1

#include <osg/observer_ptr>
#include <osg/ref_ptr>

#include <map>
#include <mutex>

namespace osgActor {

/** Wrappers by the key of what they wrap (its address), held weakly: the actors own their wrappers, the registry
  * only finds them. keyOf gives a wrapper's key as it is now; an entry whose wrapper is gone, or now wraps
  * something else, is replaced. Thread-safe. */
template <class Key, class Wrapper, Key (*keyOf)(const Wrapper&)>
class SharedObjectRegistry
{
public:
    /** The live wrapper of key, or else the one make() returns, which is the key's from now on. */
    template <class Make>
    osg::ref_ptr<Wrapper> findOrMake(const Key& key, Make make)
    {
        std::lock_guard<std::mutex> lock(_mutex);
        osg::ref_ptr<Wrapper> found = findLocked(key);
        if (found.valid()) return found;
        found = make();
        rememberLocked(key, found.get());
        return found;
    }

    /** Makes wrapper the one of its key, unless the key has a live wrapper already (readers offer each wrapper they
      * read: the first of a key stands for it). */
    void offer(Wrapper& wrapper)
    {
        const Key key = keyOf(wrapper);
        std::lock_guard<std::mutex> lock(_mutex);
        if (!findLocked(key).valid()) rememberLocked(key, &wrapper);
    }

private:
    osg::ref_ptr<Wrapper> findLocked(const Key& key)
    {
        osg::ref_ptr<Wrapper> found;
        const auto entry = _wrappers.find(key);
        if (entry != _wrappers.end() && entry->second.lock(found) && keyOf(*found) == key) return found;
        return nullptr;
    }

    void rememberLocked(const Key& key, Wrapper* wrapper)
    {
        // Dead entries go first, so the map stays as large as the number of live wrappers.
        for (auto entry = _wrappers.begin(); entry != _wrappers.end();)
        {
            osg::ref_ptr<Wrapper> alive;
            if (entry->second.lock(alive)) ++entry;
            else entry = _wrappers.erase(entry);
        }
        _wrappers[key] = wrapper;
    }

    std::mutex _mutex;
    std::map<Key, osg::observer_ptr<Wrapper>> _wrappers;
};

} // namespace osgActor

#endif
