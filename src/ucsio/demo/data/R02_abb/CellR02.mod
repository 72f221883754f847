MODULE CellR02
    ! ucsio demo cell R02: an IRB 4600 at a press table (written for the demo, not a real backup)
    ! Tools: tGripper for production, tReflector holds the laser tracker's SMR.
    PERS tooldata tGripper:=[TRUE,[[0,0,185.5],[1,0,0,0]],[2.5,[0,0,80],[1,0,0,0],0,0,0]];
    PERS tooldata tReflector:=[TRUE,[[1.5,-2,182.3],[1,0,0,0]],[0.4,[0,0,60],[1,0,0,0],0,0,0]];
    ! wobjTable: the press table as simulated (RobotStudio station, rev. C)
    TASK PERS wobjdata wobjTable:=[FALSE,TRUE,"",[[1245,-425,700],[0.953717,0,0,-0.300706]],[[0,0,0],[1,0,0,0]]];
    TASK PERS wobjdata wobjConveyor:=[FALSE,TRUE,"",[[-350,1480.5,612],[0.707107,0,0,0.707107]],[[0,0,0],[1,0,0,0]]];
    TASK PERS wobjdata wobjTurntable:=[FALSE,FALSE,"STN_1",[[0,0,0],[1,0,0,0]],[[0,0,250],[1,0,0,0]]];
    CONST robtarget pPick:=[[400,250,120],[0,0.707107,0.707107,0],[0,0,-1,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];

    PROC main()
        MoveJ Offs(pPick,0,0,100), v1000, z50, tGripper\WObj:=wobjTable;
        MoveL pPick, v200, fine, tGripper\WObj:=wobjTable;
    ENDPROC
ENDMODULE
