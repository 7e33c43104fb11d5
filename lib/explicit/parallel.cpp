#include "explicit/parallel.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace fem::par {

int threads() {
#ifdef _OPENMP
    return omp_get_max_threads();
#else
    return 1;
#endif
}

void set_threads(int n) {
#ifdef _OPENMP
    omp_set_num_threads(n);
#else
    (void)n;
#endif
}

}  // namespace fem::par
