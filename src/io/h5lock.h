/* h5lock.h: one lock for every HDF5 call of a run (private).
 *
 * Debian's serial HDF5 is built without its thread-safety option: its
 * state (open objects, the error stack, the file cache) is shared by the
 * whole process and unprotected.  Runs of the library in several threads
 * of one process (each with its own sim: they share no state of ours)
 * therefore take this lock around everything that calls HDF5 while a run
 * is built, writes its output or its checkpoints, and is freed (sim.c,
 * src/compose/build.c).  Appending a row only copies it into memory; rows
 * reach the file in a flush, under the lock.  The lock is recursive: a
 * locked call may call another. */
#ifndef BALLFILM_IO_H5LOCK_H
#define BALLFILM_IO_H5LOCK_H

void bf_h5_lock(void);
void bf_h5_unlock(void);

#endif
