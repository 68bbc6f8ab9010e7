"""Writing exemplar files with GDAL alone (no Pillow): an RGBA PNG and a float32 height twin.

Shared by the exemplar generators (make_mix_exemplars.py, make_ornament_exemplars.py) so each
sample is written the same way: GDAL's .aux.xml side files are removed, since the band's
description and unit live in the TIFF itself.
"""
import os

from osgeo import gdal


def _drop_aux(path):
    aux = path + ".aux.xml"
    if os.path.exists(aux):
        os.remove(aux)


def write_png(path, rgba, png_options=()):
    mem = gdal.GetDriverByName("MEM").Create("", rgba.shape[1], rgba.shape[0], 4, gdal.GDT_Byte)
    for band in range(4):
        mem.GetRasterBand(band + 1).WriteArray(rgba[..., band])
    mem.GetRasterBand(4).SetColorInterpretation(gdal.GCI_AlphaBand)
    gdal.GetDriverByName("PNG").CreateCopy(path, mem, options=list(png_options))
    _drop_aux(path)


def write_height(path, height_m):
    ds = gdal.GetDriverByName("GTiff").Create(path, height_m.shape[1], height_m.shape[0], 1,
                                              gdal.GDT_Float32,
                                              options=["COMPRESS=DEFLATE", "PREDICTOR=3"])
    band = ds.GetRasterBand(1)
    band.WriteArray(height_m)
    band.SetDescription("height")
    band.SetUnitType("m")
    ds = None
    _drop_aux(path)
