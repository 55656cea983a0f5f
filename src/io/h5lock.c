/* h5lock.c: the process's HDF5 lock (see h5lock.h). */
#include "io/h5lock.h"

#include <pthread.h>

static pthread_once_t once = PTHREAD_ONCE_INIT;
static pthread_mutex_t lock;

static void init_lock(void)
{
    pthread_mutexattr_t a;
    pthread_mutexattr_init(&a);
    pthread_mutexattr_settype(&a, PTHREAD_MUTEX_RECURSIVE);
    pthread_mutex_init(&lock, &a);
    pthread_mutexattr_destroy(&a);
}

void bf_h5_lock(void)
{
    pthread_once(&once, init_lock);
    pthread_mutex_lock(&lock);
}

void bf_h5_unlock(void) { pthread_mutex_unlock(&lock); }
