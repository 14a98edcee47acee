/* hdf5_dl.h - internal: the HDF5 library is loaded when first used (hdf5_dl.c defines the
 * HDF5 functions lvsim calls and forwards them; include <hdf5.h> for the functions
 * themselves). HDF5's predefined types are global variables of the library: use these
 * instead of H5T_NATIVE_DOUBLE and H5T_C_S1. Not exported. */
#ifndef LV_IO_HDF5_DL_H
#define LV_IO_HDF5_DL_H

#include <hdf5.h>

hid_t lv_h5_native_double(void); /* H5T_NATIVE_DOUBLE, or -1 without the library */
hid_t lv_h5_c_s1(void);          /* H5T_C_S1 */

/* Why the library could not be loaded (its functions then fail), or NULL when it is loaded. */
const char *lv_hdf5_error(void);

#endif
