#!/usr/bin/env python3
"""The Markdown tables of bench-frame-cost as the CSV frame_cost.py plots:

    scripts/plots/frame_cost_tables.py OUT.csv bench_frame_cost.md [more.md ...]
"""
import re,sys

out=open(sys.argv[1],'w')
out.write("path,stages,tess,not_drawn,ratio,tes_ratio,fragment_ratio,unculled_ms,split\n")
for md in sys.argv[2:]:
    path=None
    for line in open(md):
        if line.startswith('### '): path=line[4:].strip(); continue
        if path and line.startswith('| ') and not line.startswith('| tess'):
            c=[x.strip() for x in line.strip().strip('|').split('|')]
            if len(c)!=11 or not c[0].isdigit(): continue
            tess,st,x,fr,ideal,ms,ratio,share,tes,frag,split=c
            out.write('"%s","%s",%s,%.5f,%s,%s,%s,%s,"%s"\n'%(path,st,tess,float(x.rstrip('%'))/100,ratio,tes,frag,ms,split))
