"""List the element blocks ParaView's Exodus reader finds in a file, with their points, cells
and VTK cell types; exit 1 unless the file holds a block of SPHERE elements (VTK_VERTEX, 1) and
one of HEX8 elements (VTK_HEXAHEDRON, 12): a mixed PD/FE run in one file.

    pvbatch scripts/paraview_blocks.py FILE.e
"""
import sys

from paraview import servermanager as sm
from paraview.simple import ExodusIIReader

reader = ExodusIIReader(FileName=[sys.argv[1]])
reader.UpdatePipeline(list(reader.TimestepValues)[-1])
data = sm.Fetch(reader)
it = data.NewIterator()
it.InitTraversal()
seen = set()
while not it.IsDoneWithTraversal():
    block = it.GetCurrentDataObject()
    types = sorted(set(block.GetCellType(i) for i in range(block.GetNumberOfCells())))
    seen.update(types)
    print("%s: %d points, %d cells, VTK cell types %s" % (it.GetCurrentMetaData().Get(data.NAME()),
          block.GetNumberOfPoints(), block.GetNumberOfCells(), types))
    it.GoToNextItem()
sys.exit(0 if {1, 12} <= seen else 1)
