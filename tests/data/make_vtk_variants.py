#!/usr/bin/python3
"""Writes the VTU format variants of tests/data with VTK itself (run once,
outputs committed): cube5.vtu (the 5-tet cube with its tagged triangles and
"region" array) re-written by vtkXMLUnstructuredGridWriter as
  cube5_vtk_appended_raw.vtu       appended raw, UInt64 header (VTK's default)
  cube5_vtk_appended_raw_zlib.vtu  appended raw, zlib, UInt32 header
  cube5_vtk_appended_b64.vtu       appended base64, UInt32 header
  cube5_vtk_appended_b64_zlib.vtu  appended base64, zlib, UInt64 header
  cube5_vtk_binary_zlib.vtu        inline base64, zlib, UInt32 header
  cube5_vtk_binary_zlib64.vtu      inline base64, zlib, UInt64 header, 64-byte blocks
                                   (several blocks per array, a partial last one)
"""
import os

import vtk

HERE = os.path.dirname(os.path.abspath(__file__))


def write(name, mode, zlib, header64, encode=True, block=None):
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(os.path.join(HERE, "cube5.vtu"))
    reader.Update()
    w = vtk.vtkXMLUnstructuredGridWriter()
    w.SetInputData(reader.GetOutput())
    w.SetFileName(os.path.join(HERE, name))
    w.SetDataMode(mode)
    w.SetEncodeAppendedData(encode)
    w.SetHeaderTypeToUInt64() if header64 else w.SetHeaderTypeToUInt32()
    if zlib:
        w.SetCompressorTypeToZLib()
        if block:
            w.SetBlockSize(block)
    else:
        w.SetCompressorTypeToNone()
    assert w.Write() == 1


write("cube5_vtk_appended_raw.vtu", vtk.vtkXMLWriter.Appended, False, True, encode=False)
write("cube5_vtk_appended_raw_zlib.vtu", vtk.vtkXMLWriter.Appended, True, False, encode=False)
write("cube5_vtk_appended_b64.vtu", vtk.vtkXMLWriter.Appended, False, False)
write("cube5_vtk_appended_b64_zlib.vtu", vtk.vtkXMLWriter.Appended, True, True)
write("cube5_vtk_binary_zlib.vtu", vtk.vtkXMLWriter.Binary, True, False)
write("cube5_vtk_binary_zlib64.vtu", vtk.vtkXMLWriter.Binary, True, True, block=64)
