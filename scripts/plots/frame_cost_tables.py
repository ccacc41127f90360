#!/usr/bin/env python3
"""The Markdown tables of bench-frame-cost as the CSV frame_cost.py plots:

    scripts/plots/frame_cost_tables.py OUT.csv bench_frame_cost.md [more.md ...]
"""
import re,sys

out=open(sys.argv[1],'w')
out.write("path,stages,tess,not_drawn,ratio,tes_ratio,fragment_ratio,unculled_ms,free_ms,"
          "culled_ms,overhead,split\n")
for md in sys.argv[2:]:
    path=None
    for line in open(md):
        if line.startswith('### '): path=line[4:].strip(); continue
        if path and line.startswith('| ') and not line.startswith('| tess'):
            c=[x.strip() for x in line.strip().strip('|').split('|')]
            if not c[0].isdigit(): continue
            if len(c)==11:  # the table before the free-culling frame (issue 24)
                tess,st,x,fr,ideal,ms,ratio,share,tes,frag,split=c
                free=culled=overhead=''
            elif len(c)==16:
                (tess,st,x,fr,ms,free,culled,overhead,share,ratio,tes,same,frag,split,excess,
                 gpuwall)=c
                overhead='%.5f'%(float(overhead.rstrip('%'))/100)
            else: continue
            out.write('"%s","%s",%s,%.5f,%s,%s,%s,%s,%s,%s,%s,"%s"\n'%(path,st,tess,float(x.rstrip('%'))/100,ratio,tes,frag,ms,free,culled,overhead,split))
