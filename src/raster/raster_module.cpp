// Module raster: see its headers.
