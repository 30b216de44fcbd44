/* osgActorShowcase: symbol export, in OSG's shape (see osgActor/Export). */
#ifndef OSGACTORSHOWCASE_EXPORT_H
#define OSGACTORSHOWCASE_EXPORT_H 1

// Default visibility on Linux; the macro is here so that headers read like OSG's.
#define OSGACTORSHOWCASE_EXPORT

#endif
