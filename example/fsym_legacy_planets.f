C     FSYMLP: a heliocentric planetary code written the old way (its
C     own arrays, its own input reader and output loop, no modules)
C     that hands its bodies to forward-symplectic's drop-in routine
C     FSYMPL. It integrates the Sun and the outer planets of
C     data/outer_solar_system.txt (AU, days, solar masses) for 2000
C     years at h = 108.3 days (about P_Jupiter/40) with a corrected
C     method (WHK-L+C17: the lazy kernel, two forces a step, and the
C     symplectic corrector of order 17, applied only where FSYMPL hands
C     the state back) in Jacobi coordinates with the Kepler masses
C     eta_k (ICOORD = 3), prints the energy error at the outputs,
C     writes a checkpoint (the work arrays RW and IW, nothing else)
C     half way, finishes the run, then resumes a second run from the
C     checkpoint and checks that it ends bitwise where the first one
C     did.
C
C     Usage: fsym_legacy_planets [data file] [checkpoint file]
C     Build: gfortran -ffp-contract=off fsym_legacy_planets.f -lfsym
C     (doc/legacy.md; CTest: examples.fsym_legacy_planets)
      PROGRAM FSYMLP
      IMPLICIT NONE
      INTEGER NMAX, LRWMAX, LIWMAX
      PARAMETER (NMAX = 10, LRWMAX = 5000, LIWMAX = 200)
C     the method: the catalogue label (doc/legacy.md says which)
      CHARACTER*12 METHOD
      PARAMETER (METHOD = 'WHK-L+C17')
C     ICOORD: 1 Jacobi, 2 democratic, 3 Jacobi with Kepler masses eta_k
      INTEGER JACETA
      PARAMETER (JACETA = 3)
      DOUBLE PRECISION M0, G, M(NMAX), X(3,NMAX), V(3,NMAX)
      DOUBLE PRECISION XA(3,NMAX), VA(3,NMAX)
      DOUBLE PRECISION RW(LRWMAX), RW2(LRWMAX), H, E0, E, DE, DEMAX
      INTEGER IW(LIWMAX), IW2(LIWMAX)
      INTEGER N, LRW, LIW, INFO, IOUT, NOUT, NSTEP, IHALF, I, K, NDIFF
      CHARACTER*256 DFILE, CFILE
      CHARACTER*200 MSG
      PARAMETER (NOUT = 20, NSTEP = 337)
C
      DFILE = 'data/outer_solar_system.txt'
      CFILE = 'fsym_legacy_planets.ckp'
      IF (COMMAND_ARGUMENT_COUNT() .GE. 1) CALL GET_COMMAND_ARGUMENT(1,
     &    DFILE)
      IF (COMMAND_ARGUMENT_COUNT() .GE. 2) CALL GET_COMMAND_ARGUMENT(2,
     &    CFILE)
      CALL RDSYS(DFILE, NMAX, N, M0, M, G, X, V, INFO)
      IF (INFO .NE. 0) THEN
         WRITE (*, '(A)') 'FAILED: cannot read the data file'
         STOP 1
      END IF
      H = 108.3D0
      IHALF = NOUT / 2
C
C     work sizes (LRW = 30 + 13 N + 2 NOP + 3 N NSLOT), then set up
      CALL FSYMPW(METHOD, N, LRW, LIW, INFO)
      IF (INFO .NE. 0 .OR. LRW .GT. LRWMAX .OR. LIW .GT. LIWMAX) THEN
         WRITE (*, '(A,I3,2I8)') 'FAILED: work sizes', INFO, LRW, LIW
         STOP 1
      END IF
      CALL FSYMPI(METHOD, JACETA, N, M0, M, G, 0.0D0, RW, LRW, IW,
     &    LIW, INFO)
      CALL CHECK(INFO, RW, LRW, IW, LIW)
      CALL FSYMPE(N, M0, M, G, X, V, E0)
      WRITE (*, '(A,A,A,I2,A,F6.1,A)') 'method ',
     &    METHOD(1:LEN_TRIM(METHOD)), ', ', N, ' planets, h = ', H,
     &    ' d (Jacobi, Kepler masses eta_k)'
      WRITE (*, '(A,I5,A,I4)') 'work arrays: LRW =', LRW, ', LIW =', LIW
      WRITE (*, '(A)') '   years   max|dE/E| (at the outputs so far)'
C
C     the run, with output every NSTEP steps and a checkpoint half way
      DEMAX = 0.0D0
      DO 20 IOUT = 1, NOUT
         CALL FSYMPL(N, M0, M, G, X, V, H, NSTEP, RW, LRW, IW, LIW,
     &       INFO)
         CALL CHECK(INFO, RW, LRW, IW, LIW)
         CALL FSYMPE(N, M0, M, G, X, V, E)
         DE = ABS((E - E0) / E0)
         IF (DE .GT. DEMAX) DEMAX = DE
         IF (MOD(IOUT, 4) .EQ. 0) WRITE (*, '(F8.1,ES12.2)')
     &       DBLE(IOUT * NSTEP) * H / 365.25D0, DEMAX
         IF (IOUT .EQ. IHALF) THEN
            OPEN (11, FILE=CFILE, FORM='UNFORMATTED', STATUS='REPLACE')
            WRITE (11) LRW, LIW
            WRITE (11) (RW(I), I = 1, LRW), (IW(I), I = 1, LIW)
            CLOSE (11)
         END IF
   20 CONTINUE
      DO 31 K = 1, N
         DO 30 I = 1, 3
            XA(I,K) = X(I,K)
            VA(I,K) = V(I,K)
   30    CONTINUE
   31 CONTINUE
C
C     resume from the checkpoint in other arrays: the state is in it
      OPEN (11, FILE=CFILE, FORM='UNFORMATTED', STATUS='OLD')
      READ (11) LRW, LIW
      READ (11) (RW2(I), I = 1, LRW), (IW2(I), I = 1, LIW)
      CLOSE (11)
      CALL FSYMPX(N, X, V, RW2, LRW, IW2, LIW, INFO)
      CALL CHECK(INFO, RW2, LRW, IW2, LIW)
      DO 40 IOUT = IHALF + 1, NOUT
         CALL FSYMPL(N, M0, M, G, X, V, H, NSTEP, RW2, LRW, IW2, LIW,
     &       INFO)
         CALL CHECK(INFO, RW2, LRW, IW2, LIW)
   40 CONTINUE
      NDIFF = 0
      DO 51 K = 1, N
         DO 50 I = 1, 3
            IF (X(I,K) .NE. XA(I,K) .OR. V(I,K) .NE. VA(I,K))
     &          NDIFF = NDIFF + 1
   50    CONTINUE
   51 CONTINUE
      IF (NDIFF .NE. 0) THEN
         WRITE (*, '(A,I3,A)') 'FAILED: the resumed run differs in',
     &       NDIFF, ' components'
         STOP 1
      END IF
      WRITE (*, '(A)') 'resumed from the checkpoint: bitwise identical'
C
C     a mass that is not bitwise the checkpoint's is refused
      M(2) = M(2) * (1.0D0 + 1.0D-15)
      CALL FSYMPL(N, M0, M, G, X, V, H, 1, RW2, LRW, IW2, LIW, INFO)
      CALL FSYMPM(INFO, RW2, LRW, IW2, LIW, MSG)
      WRITE (*, '(A,I3,A)') 'changed mass refused: INFO =', INFO, ','
      WRITE (*, '(2X,A)') MSG(1:LEN_TRIM(MSG))
      IF (INFO .EQ. 0) STOP 1
      END
C
C     Stop with the message when INFO is not 0.
      SUBROUTINE CHECK(INFO, RW, LRW, IW, LIW)
      IMPLICIT NONE
      INTEGER INFO, LRW, LIW, IW(LIW)
      DOUBLE PRECISION RW(LRW)
      CHARACTER*200 MSG
      IF (INFO .EQ. 0) RETURN
      CALL FSYMPM(INFO, RW, LRW, IW, LIW, MSG)
      WRITE (*, '(A,I3,2A)') 'FAILED: INFO =', INFO, ': ',
     &    MSG(1:LEN_TRIM(MSG))
      STOP 1
      END
C
C     Read the system: G, then lines 'name mass x y z vx vy vz' (AU,
C     AU/day, heliocentric); the body of largest mass is the centre.
C     Lines starting with '#' are comments; the reference state after
C     the first six bodies is not read.
      SUBROUTINE RDSYS(DFILE, NMAX, N, M0, M, G, X, V, INFO)
      IMPLICIT NONE
      CHARACTER*(*) DFILE
      INTEGER NMAX, N, INFO
      DOUBLE PRECISION M0, M(NMAX), G, X(3,NMAX), V(3,NMAX)
      CHARACTER*200 LINE
      CHARACTER*16 NAME
      DOUBLE PRECISION B(7), TEND
      INTEGER NREAD, IOS, K
      INFO = 1
      N = 0
      M0 = 0.0D0
      NREAD = 0
      OPEN (10, FILE=DFILE, STATUS='OLD', IOSTAT=IOS)
      IF (IOS .NE. 0) RETURN
   10 READ (10, '(A)', IOSTAT=IOS) LINE
      IF (IOS .NE. 0) GOTO 20
      IF (LINE(1:1) .EQ. '#' .OR. LEN_TRIM(LINE) .EQ. 0) GOTO 10
      NREAD = NREAD + 1
      IF (NREAD .EQ. 1) THEN
         READ (LINE, *) G
      ELSE IF (NREAD .EQ. 2) THEN
         READ (LINE, *) TEND
      ELSE IF (NREAD .LE. 8) THEN
         READ (LINE, *) NAME, (B(K), K = 1, 7)
         IF (B(1) .GT. 0.5D0) THEN
            M0 = B(1)
         ELSE IF (N .LT. NMAX) THEN
            N = N + 1
            M(N) = B(1)
            DO 15 K = 1, 3
               X(K,N) = B(1 + K)
               V(K,N) = B(4 + K)
   15       CONTINUE
         END IF
      END IF
      IF (NREAD .LT. 8) GOTO 10
   20 CLOSE (10)
      IF (N .GE. 1 .AND. M0 .GT. 0.0D0) INFO = 0
      END
